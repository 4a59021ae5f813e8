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
  o.key_path = trim(text.substr(0, eq));
  if (eq == std::string::npos)
    fail(o, file, "expected key.path=value (e.g. bodies.0.velocity=[0,-100,0])");
  if (o.key_path.empty()) fail(o, file, "empty key path before '='");
  o.path = split_key_path(o.key_path);
  for (const auto& p : o.path)
    if (p.empty()) fail(o, file, "empty component in key path '" + o.key_path + "'");
  const std::string value = trim(text.substr(eq + 1));
  try {
    o.value = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    fail(o, file, "value '" + value + "' is not valid YAML: " + e.msg);
  }
  return o;
}

std::vector<DeckOverride> apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                                          const std::string& file) {
  std::vector<DeckOverride> parsed;
  for (const auto& text : overrides) {
    DeckOverride o = parse_override(text, file);
    if (!root.IsDefined() || root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    YAML::Node cur;
    cur.reset(root);
    for (size_t d = 0; d < o.path.size(); ++d) {
      const bool last = d + 1 == o.path.size();
      const std::string& key = o.path[d];
      if (cur.IsSequence()) {
        const size_t idx = list_index(o, file, cur, d);
        if (last) {
          cur[idx] = o.value;
        } else {
          YAML::Node next = cur[idx];
          if (next.IsNull()) {
            cur[idx] = YAML::Node(YAML::NodeType::Map);
            next.reset(cur[idx]);
          }
          cur.reset(next);
        }
      } else if (cur.IsMap()) {
        if (last) {
          cur[key] = o.value;
        } else {
          const YAML::Node& ccur = cur;
          const YAML::Node existing = ccur[key];
          if (!existing.IsDefined() || existing.IsNull()) cur[key] = YAML::Node(YAML::NodeType::Map);
          YAML::Node next = cur[key];
          cur.reset(next);
        }
      } else {
        fail(o, file, std::string("'") + joined(o.path, d) + "' is a single value, so it has no entry '" + key + "'");
      }
    }
    parsed.push_back(std::move(o));
  }
  return parsed;
}

}  // namespace ballista
