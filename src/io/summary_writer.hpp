#pragma once
// Run summary as JSON (e.g. summary.json): a small JSON value builder (null, bool, integer,
// number, string, array, object with insertion-ordered keys) and a writer that stores it
// atomically. Non-finite numbers are written as null; strings are escaped (control characters as
// \uXXXX, invalid UTF-8 bytes replaced by U+FFFD) so the file always parses.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <type_traits>
#include <vector>

namespace ballista {

class JsonValue {
 public:
  enum class Kind { Null, Bool, Int, Number, String, Array, Object };

  JsonValue() = default;  ///< null
  JsonValue(std::nullptr_t) {}
  JsonValue(bool b) : kind_(Kind::Bool), bool_(b) {}
  JsonValue(double v) : kind_(Kind::Number), number_(v) {}
  template <class T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  JsonValue(T v) : kind_(Kind::Int), int_(static_cast<std::int64_t>(v)) {}
  JsonValue(const char* s) : kind_(Kind::String), string_(s) {}
  JsonValue(std::string s) : kind_(Kind::String), string_(std::move(s)) {}
  /// Array of the elements of v (numbers, strings, bools or JsonValues).
  template <class T>
  JsonValue(const std::vector<T>& v) : kind_(Kind::Array) {
    for (const T& e : v) items_.emplace_back(e);
  }
  static JsonValue array() { JsonValue j; j.kind_ = Kind::Array; return j; }
  static JsonValue object() { JsonValue j; j.kind_ = Kind::Object; return j; }

  Kind kind() const { return kind_; }
  bool is_null() const { return kind_ == Kind::Null; }

  /// Object member, inserted as null if missing; a null value first becomes an empty object.
  JsonValue& operator[](const std::string& key);
  /// Object member; throws Error if this is not an object or has no such key.
  const JsonValue& at(const std::string& key) const;
  bool contains(const std::string& key) const;
  /// Appends to an array (a null value first becomes an empty array); returns the new element.
  JsonValue& push_back(JsonValue v);
  /// Array element; throws Error if out of range or not an array.
  const JsonValue& at(std::size_t i) const;
  /// Elements of an array or members of an object (0 otherwise).
  std::size_t size() const { return items_.size(); }
  /// Keys of an object, in insertion order.
  const std::vector<std::string>& keys() const { return keys_; }

  /// Value accessors; throw Error on a kind mismatch (as_number also accepts Int).
  bool as_bool() const;
  std::int64_t as_int() const;
  double as_number() const;
  const std::string& as_string() const;

  /// JSON text: indent >= 0 pretty-prints with that many spaces per level (arrays of scalars stay
  /// on one line), indent < 0 writes one compact line.
  std::string dump(int indent = 2) const;

 private:
  void dump_to(std::string& out, int indent, int level) const;

  Kind kind_ = Kind::Null;
  bool bool_ = false;
  std::int64_t int_ = 0;
  double number_ = 0.0;
  std::string string_;
  std::vector<std::string> keys_;  // object keys, parallel to items_
  // Array elements or object values. A deque, not a vector: adding a member keeps references to
  // the others valid (`JsonValue& st = summary["statistics"]; summary["deleted"] = ...;` then
  // st["x"] = 1 must not write into freed storage).
  std::deque<JsonValue> items_;
};

/// Every number in `v` that is NaN or infinite (written as null), as "key.path = value", key
/// paths joined by '.' below `prefix`. A result that is not available is an explicit null and is
/// not listed; a non-finite number is garbage that a run must not report as a success.
std::vector<std::string> non_finite_numbers(const JsonValue& v, const std::string& prefix = "");

/// Appends `s` to `out` as a quoted, escaped JSON string.
void json_escape_to(std::string& out, const std::string& s);

/// Builds the run summary and writes it atomically as pretty-printed JSON.
class SummaryWriter {
 public:
  JsonValue& root() { return root_; }
  const JsonValue& root() const { return root_; }
  /// Top-level member (inserted as null if missing).
  JsonValue& operator[](const std::string& key) { return root_[key]; }
  /// Writes the summary to `path` via path.tmp + rename; throws Error.
  void write(const std::string& path) const;

 private:
  JsonValue root_ = JsonValue::object();
};

}  // namespace ballista
