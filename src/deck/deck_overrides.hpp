#pragma once
// Command-line overrides of deck values (`ballista run deck.yaml --set key.path=value`).
//
// An override is "key.path=value": the path is a dot-separated list of map keys and list indices
// (bodies.0.velocity, materials.copper.yield_stress) and the value is parsed as YAML, so it may be
// a scalar, a flow list ([0,-100,0]) or a flow map ({type: box, lower: [0,0,0], upper: [1,1,1]}).
// Overrides are applied to the YAML tree before validation, in the order given; missing map keys
// (and missing intermediate maps) are created, list elements must already exist.
//
// "key.path+=value" appends to the list at the path instead of replacing it: the items of a YAML
// list value, or the value itself if it is not a list (so `segments+=[[r, l, v, t]]` appends one
// row). An absent or empty key becomes a new list; a map or a single value there is an error.
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace ballista {

struct DeckOverride {
  std::string text;               ///< the override as given, "key.path=value" or "key.path+=value"
  std::vector<std::string> path;  ///< the key path split at dots
  std::string key_path;           ///< the key path, trimmed
  YAML::Node value;               ///< the parsed value
  bool append = false;            ///< "+=": append to the list at the path instead of replacing it
};

/// Splits and parses one override; throws DeckError(file, 0, 0, key_path, ...) naming the
/// override if it has no '=', an empty path component, a value that is not valid YAML, or (with
/// "+=") an empty value.
DeckOverride parse_override(const std::string& text, const std::string& file);

/// Parses every override and applies it to `root` (which must be a map or null; null becomes a
/// map). Throws DeckError naming the override if a path goes through a scalar, indexes a list
/// with something other than an in-range index, the value cannot be parsed, or "+=" names a map
/// or a single value.
///
/// Returns what validation errors are attributed to (DeckContext::overrides): for each place the
/// overrides put a value, the override that put it there, with `path` that place. An "=" override
/// is its own entry; a "+=" override has one entry per appended item (path "probes.2", ...), so
/// that the list's other items keep their positions in the file, plus one at the list if it
/// created it. An entry at or below the path of a later "=" (or list-creating "+=") is dropped:
/// that value was replaced, and an error in the new one must name the override that set it.
std::vector<DeckOverride> apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                                          const std::string& file);

/// True if `prefix` is a leading run of components of `path` (equal paths included).
bool path_has_prefix(const std::vector<std::string>& path, const std::vector<std::string>& prefix);

/// Splits a dotted key path into components ("a.0.b" -> {"a", "0", "b"}).
std::vector<std::string> split_key_path(const std::string& key_path);

}  // namespace ballista
