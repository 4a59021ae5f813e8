#pragma once
// DeckNode: a validating view of one YAML map (or list) of an input deck.
//
// Every getter checks the type (and range) of one key, raises a DeckError pointing at the key's
// line if it is wrong, and records the value it returns (the default when the key is absent) in a
// mirror tree, so that after reading the mirror is the fully resolved deck (Scenario::resolved_yaml).
// finish() rejects keys that were never asked for, naming the closest valid key (edit distance),
// and duplicate keys. Errors inside a value set by a command-line override name the override.
#include <limits>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "core/names.hpp"
#include "core/tensor.hpp"
#include "deck/deck_overrides.hpp"
#include "deck/schema_recorder.hpp"
#include "scenario/number_range.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Parses the text of a deck: exactly one YAML document (a second one is an error, not silently
/// ignored), no tags (`!custom`, `!!str`: Ballista gives them no meaning, so they are refused),
/// and at most kMaxDeckNodes nodes counted through aliases (an alias bomb is refused before
/// anything expands it). Syntax errors become DeckErrors with the line and column.
YAML::Node load_deck_document(const std::string& yaml_text, const std::string& file_name);
inline constexpr long kMaxDeckNodes = 1'000'000;

/// Reads a plain (unquoted) YAML scalar as a finite number ("1e9", "+2", "-0.5"); false otherwise.
bool scalar_number(const YAML::Node& v, double& x);

/// What every node of one deck shares.
struct DeckContext {
  std::string file;                     ///< file name used in messages
  std::vector<DeckOverride> overrides;  ///< applied overrides, to attribute errors to them
};

/// A deck's top level as a reader starts from it, with the context that names its file.
struct DeckDocument {
  std::shared_ptr<DeckContext> ctx;
  YAML::Node root;
};

/// Loads a deck (load_deck_document), fails unless its top level is a map of sections (the message
/// names `kind`, e.g. "deck", and lists `sections`) and applies the overrides: the steps every
/// kind of deck takes before its reader.
DeckDocument open_deck_document(const std::string& yaml_text, const std::string& file_name,
                                const std::vector<std::string>& overrides, const std::string& kind,
                                const std::string& sections);

class DeckNode {
 public:
  /// The top level of a deck; fails unless `doc` is a map (an empty document counts as an empty map).
  DeckNode(std::shared_ptr<const DeckContext> ctx, YAML::Node doc);

  /// The resolved tree as the text a run keeps (Scenario::resolved_yaml), under a header that
  /// names `kind` ("deck", "drive deck") and the deck's file: every reader writes it alike.
  std::string resolved_text(const std::string& kind) const;
  /// "bodies.0.shape" ("" at the top level).
  const std::string& path() const { return path_; }
  std::string child_path(const std::string& key) const;
  /// False for an optional section that is absent from the deck.
  bool present() const { return node_.IsDefined() && !node_.IsNull(); }
  /// True if `key` is present with a non-null value (an empty value means "use the default").
  bool has(const std::string& key) const;
  const YAML::Node& yaml() const { return node_; }
  const std::string& file() const { return ctx_->file; }
  /// The deck's context, for errors about values inside custom structures (deck_fail).
  const DeckContext& context() const { return *ctx_; }

  /// Where this node is (its own position, or its parent's if it is absent).
  DeckMark mark() const;
  /// Where the value of `key` is (this node's position if the key is absent).
  DeckMark mark_of(const std::string& key) const;

  /// DeckError at this node.
  [[noreturn]] void fail(const std::string& message) const;
  /// DeckError at the value of `key` (key path this.key).
  [[noreturn]] void fail(const std::string& key, const std::string& message) const;

  // ---- nested containers -------------------------------------------------------------------
  /// A child map; an absent optional one reads as empty (every key defaulted).
  DeckNode map(const std::string& key, bool required);
  /// A child list; an absent optional one reads as empty.
  DeckNode list(const std::string& key, bool required);
  /// Number of elements (list) or entries (map).
  size_t size() const;
  /// Element i of a list; must be a map.
  DeckNode element(size_t i);
  /// Keys of a map whose entries are user-named (materials); all of them count as read.
  std::vector<std::string> entry_names();
  /// The entry `name` of a user-named map; must itself be a map.
  DeckNode entry(const std::string& name);

  // ---- values (the overloads without a default make the key required) ----------------------
  double number(const std::string& key, const NumberRange& range = {});
  double number(const std::string& key, double fallback, const NumberRange& range = {});
  /// Absent (or null) -> nullopt and nothing written to the resolved tree.
  std::optional<double> optional_number(const std::string& key, const NumberRange& range = {});
  long integer(const std::string& key, long min, long max);
  long integer(const std::string& key, long fallback, long min, long max);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key);
  std::string string(const std::string& key, const std::string& fallback);
  std::string choice(const std::string& key, const std::vector<std::string>& options);
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& options);
  /// As choice(), for a name the deck itself defines (a stage): the schema records a name, not
  /// this deck's list.
  std::string defined_name(const std::string& key, const std::string& fallback, const std::vector<std::string>& names);
  /// A list of min_count..3 numbers (missing trailing components are 0).
  Vec3 vector(const std::string& key, int min_count = 3);
  Vec3 vector(const std::string& key, const Vec3& fallback, int min_count = 3);
  std::vector<std::string> strings(const std::string& key, const std::vector<std::string>& fallback);
  /// The raw value of `key` (undefined if absent), counted as read; for custom structures,
  /// which then write their resolved form with set_resolved().
  YAML::Node raw(const std::string& key);
  void set_resolved(const std::string& key, const YAML::Node& value);

  /// Marks `key` as valid here without reading it (so it is not reported as unknown).
  void allow(const std::string& key) {
    known_->push_back(key);
    note(key, [] { return SchemaKey{}; });
  }
  /// Rejects duplicate keys and keys never asked for (naming the closest valid one).
  void finish() const;

  // ---- helpers for building resolved values -------------------------------------------------
  static YAML::Node number_node(double x);
  static YAML::Node vector_node(const Vec3& v);

 private:
  DeckNode(std::shared_ptr<const DeckContext> ctx, YAML::Node node, YAML::Node mirror, std::string path,
           YAML::Mark anchor);
  /// The value of key (undefined if absent); records the key as known.
  YAML::Node lookup(const std::string& key) const;
  /// Reports `key` as read to the active schema recorder, if there is one (deck/schema_recorder.hpp);
  /// `describe()` makes its SchemaKey, only then (a deck read for a run records nothing).
  template <class Describe>
  void note(const std::string& key, Describe describe) const {
    if (SchemaRecorder* r = active_schema_recorder()) r->key(child_path(key), describe());
  }
  /// Position of `key` itself in this map (anchor_ if absent).
  YAML::Mark key_mark(const std::string& key) const;
  /// Value node of `key` for a required key; fails if absent or null.
  YAML::Node require(const std::string& key, const char* what) const;
  /// The child map or list `key` (`what`: "a map", "a list"; `type` its YAML type), its resolved
  /// counterpart started as `empty_mirror`: the one path map() and list() share.
  DeckNode container(const std::string& key, bool required, const char* what, YAML::NodeType::value type,
                     YAML::Node empty_mirror);
  double to_number(const YAML::Node& v, const std::string& key_path, const NumberRange& range) const;
  long to_integer(const YAML::Node& v, const std::string& key, long min, long max) const;
  Vec3 to_vector(const YAML::Node& v, const std::string& key, int min_count) const;
  std::string to_choice(const YAML::Node& v, const std::string& key, const std::vector<std::string>& options) const;

  std::shared_ptr<const DeckContext> ctx_;
  YAML::Node node_;    ///< the deck's node (undefined for an absent optional section)
  YAML::Node mirror_;  ///< its resolved counterpart
  std::string path_;
  YAML::Mark anchor_;  ///< position of errors about the node as a whole (its key, or its parent's)
  std::shared_ptr<std::vector<std::string>> known_ = std::make_shared<std::vector<std::string>>();
};

/// Raises a DeckError for `key_path` at `mark`, attributing it to an override if the value came
/// from one (line 0 and the override text in the message).
[[noreturn]] void deck_fail(const DeckContext& ctx, const std::string& key_path, const YAML::Mark& mark,
                            const std::string& message);
/// The DeckMark for `key_path` at `mark` (line 0 if the value came from an override).
DeckMark deck_mark(const DeckContext& ctx, const std::string& key_path, const YAML::Mark& mark);

}  // namespace ballista
