#include "deck/deck_overrides.hpp"

#include <charconv>

#include "core/error.hpp"
#include "deck/deck_node.hpp"

namespace ballista {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string joined(const std::vector<std::string>& path, size_t count) {
  std::string out;
  for (size_t i = 0; i < count && i < path.size(); ++i) out += (i ? "." : "") + path[i];
  return out;
}

[[noreturn]] void fail(const DeckOverride& o, const std::string& file, const std::string& message) {
  // Overrides have no position in the deck file (null mark: line 0).
  const DeckContext ctx{file, {}};
  deck_fail(ctx, o.key_path, YAML::Mark::null_mark(), std::string("in override '") + o.text + "': " + message);
}

/// Index of a list element named by `key`, or throws.
size_t list_index(const DeckOverride& o, const std::string& file, const YAML::Node& list, size_t depth) {
  const std::string& key = o.path[depth];
  size_t idx = 0;
  const auto r = std::from_chars(key.data(), key.data() + key.size(), idx);
  const std::string where = depth == 0 ? std::string("the deck") : std::string("'") + joined(o.path, depth) + "'";
  if (r.ec != std::errc() || r.ptr != key.data() + key.size())
    fail(o, file, where + " is a list, so '" + key + "' must be an element index (0.." +
                      std::to_string(list.size() == 0 ? 0 : list.size() - 1) + ")");
  if (idx >= list.size())
    fail(o, file, "index " + key + " is out of range: " + where + " has " + std::to_string(list.size()) +
                      (list.size() == 1 ? " element" : " elements"));
  return idx;
}

/// Walks `root` along all but the last component of o.path, creating missing (or empty) maps on
/// the way, and returns the map or list that holds the last component.
YAML::Node parent_of_target(const YAML::Node& root, const DeckOverride& o, const std::string& file) {
  YAML::Node cur;
  cur.reset(root);
  const size_t last = o.path.size() - 1;
  for (size_t d = 0; d < last; ++d) {
    const std::string& key = o.path[d];
    if (cur.IsSequence()) {
      const size_t idx = list_index(o, file, cur, d);
      YAML::Node next = cur[idx];
      if (next.IsNull()) {
        cur[idx] = YAML::Node(YAML::NodeType::Map);
        next.reset(cur[idx]);
      }
      cur.reset(next);
    } else if (cur.IsMap()) {
      const YAML::Node& ccur = cur;  // const lookup: it must not insert the key
      const YAML::Node existing = ccur[key];
      if (!existing.IsDefined() || existing.IsNull()) cur[key] = YAML::Node(YAML::NodeType::Map);
      YAML::Node next = cur[key];
      cur.reset(next);
    } else {
      fail(o, file, "'" + joined(o.path, d) + "' is a single value, so it has no entry '" + key + "'");
    }
  }
  if (!cur.IsSequence() && !cur.IsMap())
    fail(o, file, "'" + joined(o.path, last) + "' is a single value, so it has no entry '" + o.path[last] + "'");
  return cur;
}

/// "=": puts the value at o.path, replacing what was there.
void set_value(YAML::Node parent, const DeckOverride& o, const std::string& file) {
  if (parent.IsSequence())
    parent[list_index(o, file, parent, o.path.size() - 1)] = o.value;
  else
    parent[o.path.back()] = o.value;
}

/// The list at o.path that "+=" appends to. An absent or empty key becomes a new empty list
/// (`created`), so that appending to an optional list the deck leaves out needs no "=" first.
YAML::Node target_list(YAML::Node parent, const DeckOverride& o, const std::string& file, bool& created) {
  const bool in_list = parent.IsSequence();
  const size_t idx = in_list ? list_index(o, file, parent, o.path.size() - 1) : 0;
  const auto slot = [&]() -> YAML::Node { return in_list ? parent[idx] : parent[o.path.back()]; };
  const YAML::Node& cparent = parent;  // const lookup: it must not insert the key
  const YAML::Node existing = in_list ? cparent[idx] : cparent[o.path.back()];
  created = !existing.IsDefined() || existing.IsNull();
  if (created) slot() = YAML::Node(YAML::NodeType::Sequence);
  YAML::Node list = slot();
  const std::string where = "'" + o.key_path + "'";
  if (list.IsMap())
    fail(o, file, where + " is a map, so '+=' cannot append to it (it appends to lists); use " + o.key_path +
                      ".KEY=value to set one of its entries");
  if (!list.IsSequence())
    fail(o, file, where + " is a single value, so '+=' cannot append to it (it appends to lists); use " +
                      o.key_path + "=value to replace it");
  return list;
}

/// The items "+=" appends: the items of a list value, any other value as one item.
std::vector<YAML::Node> appended_items(const YAML::Node& value) {
  if (!value.IsSequence()) return {value};
  std::vector<YAML::Node> items;
  for (const YAML::Node& item : value) items.push_back(item);
  return items;
}

/// Drops the sources at or below `path`: the value there was just replaced.
void drop_replaced(std::vector<DeckOverride>& sources, const std::vector<std::string>& path) {
  std::erase_if(sources, [&](const DeckOverride& s) { return path_has_prefix(s.path, path); });
}

/// "+=": appends the items to the list at o.path and records each item's own path as set by `o`.
void append_value(YAML::Node parent, const DeckOverride& o, const std::string& file,
                  std::vector<DeckOverride>& sources) {
  bool created = false;
  YAML::Node list = target_list(parent, o, file, created);
  if (created) {  // the whole list is the override's, as with "="
    drop_replaced(sources, o.path);
    sources.push_back(o);
  }
  for (const YAML::Node& item : appended_items(o.value)) {
    DeckOverride source = o;
    const std::string index = std::to_string(list.size());
    source.path.push_back(index);
    source.key_path += "." + index;
    source.value = item;
    sources.push_back(std::move(source));
    list.push_back(item);
  }
}

}  // namespace

std::vector<std::string> split_key_path(const std::string& key_path) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t dot = key_path.find('.', start);
    parts.push_back(trim(key_path.substr(start, dot == std::string::npos ? std::string::npos : dot - start)));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

bool path_has_prefix(const std::vector<std::string>& path, const std::vector<std::string>& prefix) {
  if (prefix.size() > path.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i)
    if (path[i] != prefix[i]) return false;
  return true;
}

DeckOverride parse_override(const std::string& text, const std::string& file) {
  DeckOverride o;
  o.text = text;
  const size_t eq = text.find('=');
  // A '+' right before the first '=' makes it "+=" (so, like a name with '=' or '.', a key ending
  // in '+' cannot be addressed; deck keys and names are words).
  o.append = eq != std::string::npos && eq > 0 && text[eq - 1] == '+';
  const std::string op = o.append ? "'+='" : "'='";
  o.key_path = trim(text.substr(0, o.append ? eq - 1 : eq));
  if (eq == std::string::npos)
    fail(o, file, "expected key.path=value or key.path+=value (e.g. bodies.0.velocity=[0,-100,0])");
  if (o.key_path.empty()) fail(o, file, "empty key path before " + op);
  o.path = split_key_path(o.key_path);
  for (const auto& p : o.path)
    if (p.empty()) fail(o, file, "empty component in key path '" + o.key_path + "'");
  const std::string value = trim(text.substr(eq + 1));
  try {
    o.value = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    fail(o, file, "value '" + value + "' is not valid YAML: " + e.msg);
  }
  // An empty item is never a valid list entry; more likely the value was lost (shell quoting).
  if (o.append && o.value.IsNull())
    fail(o, file, "nothing to append after '+=': expected a value or a list of values (e.g. " + o.key_path +
                      "+=[a, b])");
  return o;
}

std::vector<DeckOverride> apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                                          const std::string& file) {
  std::vector<DeckOverride> sources;
  for (const auto& text : overrides) {
    const DeckOverride o = parse_override(text, file);
    if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    const YAML::Node parent = parent_of_target(root, o, file);
    if (o.append) {
      append_value(parent, o, file, sources);
    } else {
      set_value(parent, o, file);
      drop_replaced(sources, o.path);
      sources.push_back(o);
    }
  }
  return sources;
}

}  // namespace ballista
