#include "deck/deck_node.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

namespace ballista {

namespace {

/// A key as DeckNode reports it to the schema recorder (deck/schema_recorder.hpp).
SchemaKey key_of(SchemaKey::Kind kind, bool required, std::string fallback = "", NumberRange range = {},
                 std::vector<std::string> choices = {}, int min_items = 0) {
  SchemaKey k;
  k.kind = kind;
  k.required = required;
  k.fallback = std::move(fallback);
  k.range = std::move(range);
  k.choices = std::move(choices);
  k.min_items = min_items;
  return k;
}

/// One pass over the parser's events (nothing is built, no alias is expanded): at most one
/// document, no tags, no alias inside its own anchor, and at most kMaxDeckNodes nodes counted
/// through aliases (each alias counts the size of what it refers to).
class DeckEventCheck : public YAML::EventHandler {
 public:
  explicit DeckEventCheck(std::string file) : file_(std::move(file)) {}

  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents_ > 1)
      fail(mark, "the file holds more than one YAML document (separated by '---'); a deck is one document");
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override { leaf(mark, anchor); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    for (const Frame& f : stack_)
      if (f.anchor == anchor && anchor != YAML::NullAnchor)
        fail(mark, "an alias refers to the collection that contains it (a recursive alias)");
    const auto it = sizes_.find(anchor);
    add(mark, it == sizes_.end() ? 1.0 : it->second);
  }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor, const std::string&) override {
    check_tag(mark, tag);
    leaf(mark, anchor);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, tag, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, tag, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    YAML::anchor_t anchor;
    double nodes;  ///< nodes inside, aliases expanded
    YAML::Mark mark;
  };
  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& message) const {
    throw DeckError(file_, mark.line + 1, mark.column + 1, "", message);
  }
  void check_tag(const YAML::Mark& mark, const std::string& tag) const {
    // "?" = plain untagged node, "!" = quoted scalar (non-specific tag); anything else was
    // written as a tag in the deck.
    if (!tag.empty() && tag != "?" && tag != "!")
      fail(mark, "YAML tag '" + shorten(tag) + "' is not supported in a deck (Ballista reads plain values; "
                 "remove the tag)");
  }
  void add(const YAML::Mark& mark, double n) {
    total_ += n;
    if (total_ > static_cast<double>(kMaxDeckNodes))
      fail(mark, "the deck expands to more than " + std::to_string(kMaxDeckNodes) +
                     " YAML nodes (aliases referring to aliases?); a deck that large is refused");
    if (!stack_.empty()) stack_.back().nodes += n;
  }
  void leaf(const YAML::Mark& mark, YAML::anchor_t anchor) {
    if (anchor != YAML::NullAnchor) sizes_[anchor] = 1.0;
    add(mark, 1.0);
  }
  void open(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor) {
    check_tag(mark, tag);
    if (stack_.size() >= kMaxDepth) fail(mark, "the deck nests deeper than " + std::to_string(kMaxDepth) + " levels");
    add(mark, 1.0);
    stack_.push_back({anchor, 0.0, mark});
  }
  void close() {
    const Frame f = stack_.back();
    stack_.pop_back();
    if (f.anchor != YAML::NullAnchor) sizes_[f.anchor] = f.nodes + 1.0;
    // The collection's contents count in its parent too (the collection itself was counted at open).
    if (!stack_.empty()) stack_.back().nodes += f.nodes;
  }

  static constexpr size_t kMaxDepth = 200;
  std::string file_;
  int documents_ = 0;
  double total_ = 0.0;
  std::vector<Frame> stack_;
  std::map<YAML::anchor_t, double> sizes_;
};

}  // namespace

YAML::Node load_deck_document(const std::string& yaml_text, const std::string& file_name) {
  const auto syntax = [&](const YAML::Exception& e) {
    return DeckError(file_name, e.mark.line >= 0 ? e.mark.line + 1 : 0, e.mark.column >= 0 ? e.mark.column + 1 : 0,
                     "", "invalid YAML: " + e.msg);
  };
  try {
    // Checks first, on the event stream: a second document is found by asking for it once (not by
    // YAML::LoadAll, which never returns on some malformed input, yaml-cpp issue 1040).
    std::istringstream in(yaml_text);
    YAML::Parser parser(in);
    DeckEventCheck check(file_name);
    if (parser.HandleNextDocument(check)) parser.HandleNextDocument(check);
    return YAML::Load(yaml_text);
  } catch (const DeckError&) {
    throw;
  } catch (const YAML::Exception& e) {
    throw syntax(e);
  }
}

DeckDocument open_deck_document(const std::string& yaml_text, const std::string& file_name,
                                const std::vector<std::string>& overrides, const std::string& kind,
                                const std::string& sections) {
  DeckDocument d{std::make_shared<DeckContext>(), load_deck_document(yaml_text, file_name)};
  d.ctx->file = file_name;
  if (d.root.IsDefined() && !d.root.IsNull() && !d.root.IsMap())
    throw DeckError(file_name, d.root.Mark().line + 1, d.root.Mark().column + 1, "",
                    "expected the " + kind + " to be a map of sections (" + sections + ")");
  d.ctx->overrides = apply_overrides(d.root, overrides, file_name);
  return d;
}

bool scalar_number(const YAML::Node& v, double& x) {
  if (!v.IsScalar() || v.Tag() == "!") return false;
  const std::string& s = v.Scalar();
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (b != e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, x);
  return b != e && r.ec == std::errc() && r.ptr == e && std::isfinite(x);
}

// ---- error positions ------------------------------------------------------------------------

namespace {

/// The most specific override whose path is `path` or encloses it.
const DeckOverride* enclosing_override(const DeckContext& ctx, const std::vector<std::string>& path) {
  const DeckOverride* best = nullptr;
  for (const auto& o : ctx.overrides)
    if (path_has_prefix(path, o.path) && (!best || o.path.size() >= best->path.size())) best = &o;
  return best;
}

/// An override that created the (previously absent) map holding `path`: one whose path shares the
/// longest leading part with it.
const DeckOverride* creating_override(const DeckContext& ctx, std::vector<std::string> path) {
  for (; !path.empty(); path.pop_back())
    for (const auto& o : ctx.overrides)
      if (path_has_prefix(o.path, path)) return &o;
  return nullptr;
}

bool is_null_mark(const YAML::Mark& m) { return m.line < 0 || m.column < 0; }

}  // namespace

DeckMark deck_mark(const DeckContext& ctx, const std::string& key_path, const YAML::Mark& mark) {
  DeckMark m{ctx.file, key_path, 0, 0};
  const auto path = split_key_path(key_path);
  if (!key_path.empty() && enclosing_override(ctx, path)) return m;
  if (is_null_mark(mark)) return m;
  m.line = mark.line + 1;
  m.column = mark.column + 1;
  return m;
}

void deck_fail(const DeckContext& ctx, const std::string& key_path, const YAML::Mark& mark,
               const std::string& message) {
  const auto path = split_key_path(key_path);
  if (!key_path.empty()) {
    if (const DeckOverride* o = enclosing_override(ctx, path))
      throw DeckError(ctx.file, 0, 0, key_path, message + " (value from override '" + o->text + "')");
  }
  if (is_null_mark(mark)) {
    const DeckOverride* o = key_path.empty() ? nullptr : creating_override(ctx, path);
    throw DeckError(ctx.file, 0, 0, key_path,
                    o ? message + " (section created by override '" + o->text + "')" : message);
  }
  throw DeckError(ctx.file, mark.line + 1, mark.column + 1, key_path, message);
}

// ---- DeckNode -------------------------------------------------------------------------------

namespace {

YAML::Node flow_sequence() {
  YAML::Node s(YAML::NodeType::Sequence);
  s.SetStyle(YAML::EmitterStyle::Flow);
  return s;
}

bool quoted(const YAML::Node& v) { return v.Tag() == "!"; }

const char* kind(const YAML::Node& v) {
  if (v.IsMap()) return "a map";
  if (v.IsSequence()) return "a list";
  if (v.IsNull()) return "an empty value";
  return nullptr;
}

/// "expected X, got Y" where Y describes a non-scalar or quotes the scalar.
std::string got(const YAML::Node& v) {
  if (const char* k = kind(v)) return std::string(", got ") + k;
  return ", got '" + shorten(v.Scalar()) + "'";
}

}  // namespace

DeckNode::DeckNode(std::shared_ptr<const DeckContext> ctx, YAML::Node doc)
    : ctx_(std::move(ctx)), node_(doc), mirror_(YAML::NodeType::Map) {
  if (node_.IsDefined() && !node_.IsNull() && !node_.IsMap())
    deck_fail(*ctx_, "", node_.Mark(), "expected the deck to be a map of sections (simulation, grid, ...)");
  anchor_ = node_.IsDefined() ? node_.Mark() : YAML::Mark::null_mark();
}

DeckNode::DeckNode(std::shared_ptr<const DeckContext> ctx, YAML::Node node, YAML::Node mirror, std::string path,
                   YAML::Mark anchor)
    : ctx_(std::move(ctx)), node_(node), mirror_(mirror), path_(std::move(path)), anchor_(anchor) {}

std::string DeckNode::child_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

YAML::Node DeckNode::lookup(const std::string& key) const {
  if (std::find(known_->begin(), known_->end(), key) == known_->end()) known_->push_back(key);
  if (!node_.IsDefined() || !node_.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& n = node_;
  const YAML::Node v = n[key];  // an invalid ("zombie") node if absent: normalise to undefined
  return v.IsDefined() ? v : YAML::Node(YAML::NodeType::Undefined);
}

bool DeckNode::has(const std::string& key) const {
  if (!node_.IsDefined() || !node_.IsMap()) return false;
  const YAML::Node& n = node_;
  const YAML::Node v = n[key];
  return v.IsDefined() && !v.IsNull();
}

DeckMark DeckNode::mark() const { return deck_mark(*ctx_, path_, anchor_); }

YAML::Mark DeckNode::key_mark(const std::string& key) const {
  if (present() && node_.IsMap())
    for (auto it = node_.begin(); it != node_.end(); ++it)
      if (it->first.IsScalar() && it->first.Scalar() == key) return it->first.Mark();
  return anchor_;
}

DeckMark DeckNode::mark_of(const std::string& key) const {
  if (!has(key)) {
    DeckMark m = mark();
    m.key_path = child_path(key);
    return m;
  }
  const YAML::Node& n = node_;
  return deck_mark(*ctx_, child_path(key), n[key].Mark());
}

void DeckNode::fail(const std::string& message) const { deck_fail(*ctx_, path_, anchor_, message); }

void DeckNode::fail(const std::string& key, const std::string& message) const {
  if (has(key)) {
    const YAML::Node& n = node_;
    deck_fail(*ctx_, child_path(key), n[key].Mark(), message);
  }
  deck_fail(*ctx_, child_path(key), anchor_, message);
}

YAML::Node DeckNode::require(const std::string& key, const char* what) const {
  YAML::Node v = lookup(key);
  if (!v.IsDefined()) {
    const std::string where = path_.empty() ? std::string("the deck") : path_;
    // A misspelt required key is better reported as the misspelling than as a missing key.
    if (present() && node_.IsMap()) {
      std::vector<std::string> unread;
      for (auto it = node_.begin(); it != node_.end(); ++it)
        if (it->first.IsScalar() && std::find(known_->begin(), known_->end(), it->first.Scalar()) == known_->end())
          unread.push_back(it->first.Scalar());
      for (const auto& u : unread)
        if (closest_name(u, {key}) == key)
          deck_fail(*ctx_, child_path(u), key_mark(u),
                    "unknown key '" + shorten(u) + "' in " + where + "; did you mean '" + key + "'?");
    }
    deck_fail(*ctx_, child_path(key), anchor_,
              "missing required key '" + key + "' in " + where + " (expected " + what + ")");
  }
  if (v.IsNull()) deck_fail(*ctx_, child_path(key), v.Mark(), std::string("expected ") + what + ", got an empty value");
  return v;
}

std::string DeckNode::resolved_text(const std::string& kind) const {
  std::ostringstream os;
  os << "# Fully resolved " << kind << " (every default filled) of " << ctx_->file << ", written by ballista.\n";
  os << YAML::Dump(mirror_) << "\n";
  return os.str();
}

DeckNode DeckNode::container(const std::string& key, bool required, const char* what, YAML::NodeType::value type,
                             YAML::Node empty_mirror) {
  YAML::Node v = required ? require(key, what) : lookup(key);
  const YAML::Mark anchor = key_mark(key);
  if (v.IsDefined() && !v.IsNull() && v.Type() != type)
    deck_fail(*ctx_, child_path(key), v.Mark(), std::string("expected ") + what + got(v));
  if (v.IsNull()) v = YAML::Node(YAML::NodeType::Undefined);
  note(key, [&] { return key_of(type == YAML::NodeType::Map ? SchemaKey::Kind::Object : SchemaKey::Kind::List, required); });
  mirror_[key] = empty_mirror;
  return DeckNode(ctx_, v, mirror_[key], child_path(key), anchor);
}

DeckNode DeckNode::map(const std::string& key, bool required) {
  return container(key, required, "a map", YAML::NodeType::Map, YAML::Node(YAML::NodeType::Map));
}

DeckNode DeckNode::list(const std::string& key, bool required) {
  return container(key, required, "a list", YAML::NodeType::Sequence, flow_sequence());
}

size_t DeckNode::size() const { return present() ? node_.size() : 0; }

DeckNode DeckNode::element(size_t i) {
  const YAML::Node& n = node_;
  YAML::Node v = n[i];
  const std::string path = child_path(std::to_string(i));
  if (!v.IsMap()) deck_fail(*ctx_, path, v.Mark(), "expected a map" + got(v));
  if (mirror_.size() == 0) mirror_.SetStyle(YAML::EmitterStyle::Block);
  YAML::Node m(YAML::NodeType::Map);
  mirror_.push_back(m);
  return DeckNode(ctx_, v, mirror_[mirror_.size() - 1], path, v.Mark());
}

std::vector<std::string> DeckNode::entry_names() {
  if (SchemaRecorder* r = active_schema_recorder()) r->names(path_);
  std::vector<std::string> names;
  if (!present()) return names;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    if (!it->first.IsScalar()) deck_fail(*ctx_, path_, it->first.Mark(), "expected a name as the key");
    const std::string name = it->first.Scalar();
    if (std::find(names.begin(), names.end(), name) != names.end())
      deck_fail(*ctx_, child_path(name), it->first.Mark(), "duplicate name '" + shorten(name) + "' in " + path_);
    names.push_back(name);
    known_->push_back(name);
  }
  return names;
}

DeckNode DeckNode::entry(const std::string& name) {
  YAML::Node v = require(name, "a map");
  if (!v.IsMap()) deck_fail(*ctx_, child_path(name), v.Mark(), "expected a map" + got(v));
  mirror_[name] = YAML::Node(YAML::NodeType::Map);
  // Errors about the entry as a whole point at its name.
  return DeckNode(ctx_, v, mirror_[name], child_path(name), key_mark(name));
}

// ---- scalar conversions -----------------------------------------------------------------------

double DeckNode::to_number(const YAML::Node& v, const std::string& key, const NumberRange& range) const {
  const std::string path = child_path(key);
  std::string what = "a number";
  if (const std::string r = range.describe(); !r.empty()) what += " " + r;
  double x = 0.0;
  if (!scalar_number(v, x)) deck_fail(*ctx_, path, v.Mark(), "expected " + what + got(v));
  if (!range.contains(x)) deck_fail(*ctx_, path, v.Mark(), "expected " + what + ", got " + format_number(x));
  return x;
}

long DeckNode::to_integer(const YAML::Node& v, const std::string& key, long min, long max) const {
  const std::string path = child_path(key);
  std::string what = "an integer";
  if (min != std::numeric_limits<long>::min() && max < std::numeric_limits<int>::max())
    what += " in " + std::to_string(min) + ".." + std::to_string(max);
  else if (min != std::numeric_limits<long>::min())
    what += " >= " + std::to_string(min);
  if (!v.IsScalar() || quoted(v)) deck_fail(*ctx_, path, v.Mark(), "expected " + what + got(v));
  const std::string& s = v.Scalar();
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (b != e && *b == '+') ++b;
  long x = 0;
  const auto r = std::from_chars(b, e, x);
  if (r.ec != std::errc() || r.ptr != e || b == e) deck_fail(*ctx_, path, v.Mark(), "expected " + what + got(v));
  if (x < min || x > max) deck_fail(*ctx_, path, v.Mark(), "expected " + what + ", got " + std::to_string(x));
  return x;
}

Vec3 DeckNode::to_vector(const YAML::Node& v, const std::string& key, int min_count) const {
  const std::string path = child_path(key);
  const std::string what =
      min_count >= 3 ? "a list of 3 numbers" : "a list of " + std::to_string(min_count) + " or 3 numbers";
  if (!v.IsSequence() || v.size() < static_cast<size_t>(min_count) || v.size() > 3) {
    std::string g = got(v);
    if (v.IsSequence()) g = ", got a list of " + std::to_string(v.size());
    deck_fail(*ctx_, path, v.Mark(), "expected " + what + g);
  }
  Vec3 out;
  for (size_t i = 0; i < v.size(); ++i) {
    const YAML::Node c = v[i];
    const std::string cpath = path + "." + std::to_string(i);
    double x = 0.0;
    if (!scalar_number(c, x)) deck_fail(*ctx_, cpath, c.Mark(), "expected a number" + got(c));
    out[static_cast<int>(i)] = x;
  }
  return out;
}

std::string DeckNode::to_choice(const YAML::Node& v, const std::string& key,
                                const std::vector<std::string>& options) const {
  const std::string path = child_path(key);
  if (!v.IsScalar()) deck_fail(*ctx_, path, v.Mark(), "expected one of: " + join_names(options) + got(v));
  const std::string& s = v.Scalar();
  if (std::find(options.begin(), options.end(), s) == options.end()) {
    std::string hint;
    if (const std::string best = closest_name(s, options); !best.empty()) hint = " (did you mean '" + best + "'?)";
    deck_fail(*ctx_, path, v.Mark(), "expected one of: " + join_names(options) + ", got '" + s + "'" + hint);
  }
  return s;
}

// ---- typed getters --------------------------------------------------------------------------

YAML::Node DeckNode::number_node(double x) { return YAML::Node(format_number(x)); }

YAML::Node DeckNode::vector_node(const Vec3& v) {
  YAML::Node s = flow_sequence();
  for (int i = 0; i < 3; ++i) s.push_back(format_number(v[i]));
  return s;
}

double DeckNode::number(const std::string& key, const NumberRange& range) {
  std::string what = "a number";
  if (const std::string r = range.describe(); !r.empty()) what += " " + r;
  const double x = to_number(require(key, what.c_str()), key, range);
  note(key, [&] { return key_of(SchemaKey::Kind::Number, true, "", range); });
  mirror_[key] = number_node(x);
  return x;
}

double DeckNode::number(const std::string& key, double fallback, const NumberRange& range) {
  const YAML::Node v = lookup(key);
  const double x = v.IsDefined() && !v.IsNull() ? to_number(v, key, range) : fallback;
  note(key, [&] { return key_of(SchemaKey::Kind::Number, false, format_number(fallback), range); });
  mirror_[key] = number_node(x);
  return x;
}

std::optional<double> DeckNode::optional_number(const std::string& key, const NumberRange& range) {
  const YAML::Node v = lookup(key);
  note(key, [&] { return key_of(SchemaKey::Kind::Number, false, "", range); });
  if (!v.IsDefined() || v.IsNull()) return std::nullopt;
  const double x = to_number(v, key, range);
  mirror_[key] = number_node(x);
  return x;
}

long DeckNode::integer(const std::string& key, long min, long max) {
  const long x = to_integer(require(key, "an integer"), key, min, max);
  note(key, [&] { return key_of(SchemaKey::Kind::Integer, true, "", NumberRange::between(min, max)); });
  mirror_[key] = std::to_string(x);
  return x;
}

long DeckNode::integer(const std::string& key, long fallback, long min, long max) {
  const YAML::Node v = lookup(key);
  const long x = v.IsDefined() && !v.IsNull() ? to_integer(v, key, min, max) : fallback;
  note(key, [&] {
    return key_of(SchemaKey::Kind::Integer, false, std::to_string(fallback), NumberRange::between(min, max));
  });
  mirror_[key] = std::to_string(x);
  return x;
}

bool DeckNode::boolean(const std::string& key, bool fallback) {
  const YAML::Node v = lookup(key);
  note(key, [&] { return key_of(SchemaKey::Kind::Boolean, false, fallback ? "true" : "false"); });
  bool x = fallback;
  if (v.IsDefined() && !v.IsNull()) {
    const std::string s = v.IsScalar() && !quoted(v) ? v.Scalar() : std::string();
    if (s == "true" || s == "True" || s == "TRUE")
      x = true;
    else if (s == "false" || s == "False" || s == "FALSE")
      x = false;
    else
      deck_fail(*ctx_, child_path(key), v.Mark(), "expected true or false" + got(v));
  }
  mirror_[key] = x ? "true" : "false";
  return x;
}

std::string DeckNode::string(const std::string& key) {
  const YAML::Node v = require(key, "a name");
  if (!v.IsScalar() || v.Scalar().empty()) deck_fail(*ctx_, child_path(key), v.Mark(), "expected a name" + got(v));
  note(key, [&] { return key_of(SchemaKey::Kind::String, true); });
  mirror_[key] = v.Scalar();
  return v.Scalar();
}

std::string DeckNode::string(const std::string& key, const std::string& fallback) {
  const YAML::Node v = lookup(key);
  note(key, [&] { return key_of(SchemaKey::Kind::String, false, fallback); });
  std::string x = fallback;
  if (v.IsDefined() && !v.IsNull()) {
    if (!v.IsScalar()) deck_fail(*ctx_, child_path(key), v.Mark(), "expected a name" + got(v));
    x = v.Scalar();
  }
  mirror_[key] = x;
  return x;
}

std::string DeckNode::choice(const std::string& key, const std::vector<std::string>& options) {
  const std::string what = "one of: " + join_names(options);
  const std::string x = to_choice(require(key, what.c_str()), key, options);
  note(key, [&] { return key_of(SchemaKey::Kind::Choice, true, "", NumberRange{}, options); });
  mirror_[key] = x;
  return x;
}

std::string DeckNode::choice(const std::string& key, const std::string& fallback,
                             const std::vector<std::string>& options) {
  const YAML::Node v = lookup(key);
  const std::string x = v.IsDefined() && !v.IsNull() ? to_choice(v, key, options) : fallback;
  note(key, [&] { return key_of(SchemaKey::Kind::Choice, false, fallback, NumberRange{}, options); });
  mirror_[key] = x;
  return x;
}

std::string DeckNode::defined_name(const std::string& key, const std::string& fallback,
                                   const std::vector<std::string>& names) {
  const YAML::Node v = lookup(key);
  const std::string x = v.IsDefined() && !v.IsNull() ? to_choice(v, key, names) : fallback;
  note(key, [&] { return key_of(SchemaKey::Kind::String, false, fallback); });
  mirror_[key] = x;
  return x;
}

Vec3 DeckNode::vector(const std::string& key, int min_count) {
  const std::string what = min_count >= 3 ? "a list of 3 numbers" : "a list of 2 or 3 numbers";
  const Vec3 x = to_vector(require(key, what.c_str()), key, min_count);
  note(key, [&] { return key_of(SchemaKey::Kind::Vector, true, "", NumberRange{}, {}, min_count); });
  mirror_[key] = vector_node(x);
  return x;
}

Vec3 DeckNode::vector(const std::string& key, const Vec3& fallback, int min_count) {
  const YAML::Node v = lookup(key);
  const Vec3 x = v.IsDefined() && !v.IsNull() ? to_vector(v, key, min_count) : fallback;
  note(key, [&] { return key_of(SchemaKey::Kind::Vector, false, "", NumberRange{}, {}, min_count); });
  mirror_[key] = vector_node(x);
  return x;
}

std::vector<std::string> DeckNode::strings(const std::string& key, const std::vector<std::string>& fallback) {
  const YAML::Node v = lookup(key);
  note(key, [&] { return key_of(SchemaKey::Kind::Strings, false); });
  std::vector<std::string> x = fallback;
  if (v.IsDefined() && !v.IsNull()) {
    if (!v.IsSequence()) deck_fail(*ctx_, child_path(key), v.Mark(), "expected a list of names" + got(v));
    x.clear();
    for (size_t i = 0; i < v.size(); ++i) {
      const YAML::Node c = v[i];
      if (!c.IsScalar() || c.Scalar().empty())
        deck_fail(*ctx_, child_path(key) + "." + std::to_string(i), c.Mark(), "expected a name" + got(c));
      x.push_back(c.Scalar());
    }
  }
  YAML::Node s = flow_sequence();
  for (const auto& n : x) s.push_back(n);
  mirror_[key] = s;
  return x;
}

YAML::Node DeckNode::raw(const std::string& key) {
  note(key, [] { return SchemaKey{}; });
  return lookup(key);
}

void DeckNode::set_resolved(const std::string& key, const YAML::Node& value) { mirror_[key] = value; }

void DeckNode::finish() const {
  if (!present() || !node_.IsMap()) return;
  std::vector<std::string> seen;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const YAML::Node k = it->first;  // a copy: it-> yields a temporary
    if (!k.IsScalar()) deck_fail(*ctx_, path_, k.Mark(), "expected a key name" + got(k));
    const std::string& name = k.Scalar();
    const std::string where = path_.empty() ? std::string("the deck") : path_;
    if (std::find(seen.begin(), seen.end(), name) != seen.end())
      deck_fail(*ctx_, child_path(name), k.Mark(), "duplicate key '" + shorten(name) + "' in " + where);
    seen.push_back(name);
    if (std::find(known_->begin(), known_->end(), name) == known_->end())
      deck_fail(*ctx_, child_path(name), k.Mark(),
                "unknown key '" + shorten(name) + "' in " + where + suggest(name, *known_));
  }
}

}  // namespace ballista
