#pragma once
// What the deck readers ask for, recorded for the deck's JSON Schema (`ballista schema`,
// run/deck_schema.hpp). The readers are the one description of a deck: rather than a second,
// hand-written list that would drift from them, every DeckNode getter reports the key it reads,
// its kind, range, unit, choices and default to the recorder active at the time, if any. Reading
// decks with a recorder active collects the keys of every branch those decks take.
#include <map>
#include <set>
#include <string>
#include <vector>

#include "scenario/number_range.hpp"

namespace ballista {

/// One key as a reader asks for it.
struct SchemaKey {
  enum class Kind { Any, Number, Integer, Boolean, String, Choice, Vector, Strings, Object, List, Names };
  Kind kind = Kind::Any;
  NumberRange range;                 ///< Number (unit, bounds), Integer (bounds)
  std::vector<std::string> choices;  ///< Choice
  int min_items = 0;                 ///< Vector: the fewest components given
  std::string fallback;              ///< the default as the resolved deck writes it; "" if required or none
  bool required = false;
};

/// Adds `k` to the kinds one key was read with, unless one of the same kind, choices and range is
/// there already (then the fewer vector components of the two count; the first one's unit and
/// default stay: one key read twice, or by a reader and a registry).
void add_schema_key(std::vector<SchemaKey>& kinds, const SchemaKey& k);

/// Keys by pattern: list elements as "[]" and user-named entries as "*" (bodies[].shape.radius,
/// materials.*.density).
class SchemaRecorder {
 public:
  /// The key `key_path` (a DeckNode path, "bodies.0.shape.radius") as a reader asked for it. A
  /// pattern read with two kinds keeps both (the schema then allows either).
  void key(const std::string& key_path, SchemaKey k);
  /// `path` is a map of user-named entries (materials): its keys become "*".
  void names(const std::string& path);
  /// The pattern of a DeckNode path.
  std::string pattern(const std::string& path) const;
  const std::map<std::string, std::vector<SchemaKey>>& keys() const { return keys_; }

 private:
  std::map<std::string, std::vector<SchemaKey>> keys_;
  std::set<std::string> names_;  ///< patterns of the user-named maps
};

/// The recorder DeckNode reports to, or null (the normal case: nothing is recorded).
SchemaRecorder* active_schema_recorder();

/// Makes `r` the active recorder while alive (one at a time; not thread-safe: for the schema
/// command, which reads decks one after the other).
class SchemaRecording {
 public:
  explicit SchemaRecording(SchemaRecorder& r);
  ~SchemaRecording();
  SchemaRecording(const SchemaRecording&) = delete;
  SchemaRecording& operator=(const SchemaRecording&) = delete;

 private:
  SchemaRecorder* previous_;
};

}  // namespace ballista
