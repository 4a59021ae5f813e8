#include "deck/material_presets.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/data_dir.hpp"
#include "core/error.hpp"
#include "deck/deck_node.hpp"

namespace ballista {

namespace {

const std::vector<std::string> kTopKeys{"schema_version", "presets"};
const std::vector<std::string> kPresetKeys{"model", "description", "parameters", "sources", "cross_checks", "notes"};
const std::vector<std::string> kSourceKeys{"keys", "cite", "via", "confidence"};
constexpr int kSchemaVersion = 1;

/// 1-based line and column of a node (0 if it has no position, e.g. an absent key).
int line_of(const YAML::Mark& m) { return m.line >= 0 ? m.line + 1 : 0; }
int column_of(const YAML::Mark& m) { return m.column >= 0 ? m.column + 1 : 0; }

/// "a map", "a list", "nothing" or the quoted scalar - for "expected X, got Y" messages.
std::string kind_of(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "nothing";
  if (n.IsMap()) return "a map";
  if (n.IsSequence()) return "a list";
  return "'" + n.Scalar() + "'";
}

/// Validates one presets document; every failure names the file, line and key path.
class PresetParser {
 public:
  explicit PresetParser(std::string file) : file_(std::move(file)) {}

  std::vector<MaterialPreset> parse(const YAML::Node& root) {
    if (!root.IsDefined() || root.IsNull())
      fail("", root, "empty presets file: expected 'presets:' with at least one preset");
    if (!root.IsMap()) fail("", root, "expected a map with 'schema_version' and 'presets', got " + kind_of(root));
    check_keys(root, "", kTopKeys);
    const YAML::Node version = root["schema_version"];
    double v = 0.0;
    if (!scalar_number(version, v) || v != kSchemaVersion)
      fail("schema_version", version.IsDefined() ? version : root,
           "expected schema_version: " + std::to_string(kSchemaVersion) + ", got " + kind_of(version));
    const YAML::Node presets = root["presets"];
    if (!presets.IsMap() || presets.size() == 0)
      fail("presets", presets.IsDefined() ? presets : root, "expected a map of named presets, got " + kind_of(presets));
    std::vector<MaterialPreset> out;
    for (auto it = presets.begin(); it != presets.end(); ++it) out.push_back(preset(it->first, it->second));
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const YAML::Node& at, const std::string& message) const {
    const YAML::Mark m = at.IsDefined() ? at.Mark() : YAML::Mark::null_mark();
    throw DeckError(file_, line_of(m), column_of(m), path, message);
  }

  /// Rejects duplicate keys and keys not in `allowed` (naming the closest allowed one).
  void check_keys(const YAML::Node& map, const std::string& path, const std::vector<std::string>& allowed) const {
    std::set<std::string> seen;
    for (auto it = map.begin(); it != map.end(); ++it) {
      const std::string key = it->first.as<std::string>();
      const std::string where = path.empty() ? key : path + "." + key;
      if (!seen.insert(key).second) fail(where, it->first, "duplicate key '" + key + "'");
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), key) == allowed.end())
        fail(where, it->first, "unknown key '" + key + "'" + suggest(key, allowed));
    }
  }

  std::string word(const YAML::Node& n, const std::string& path, bool required) const {
    if (!n.IsDefined() || n.IsNull()) {
      if (required) fail(path, n, "missing '" + path.substr(path.rfind('.') + 1) + "'");
      return {};
    }
    if (!n.IsScalar() || n.Scalar().empty()) fail(path, n, "expected a non-empty text, got " + kind_of(n));
    return n.Scalar();
  }

  MaterialPreset preset(const YAML::Node& key, const YAML::Node& node) {
    MaterialPreset p;
    p.name = key.as<std::string>();
    p.file = file_;
    p.line = line_of(key.Mark());
    const std::string path = "presets." + p.name;
    if (!names_.insert(p.name).second) fail(path, key, "duplicate preset '" + p.name + "'");
    if (!node.IsMap())
      fail(path, node.IsDefined() && !node.IsNull() ? node : key,
           "expected a map (model, parameters, sources), got " + kind_of(node));
    check_keys(node, path, kPresetKeys);
    // A missing key is reported at the preset's name (node[...] of an absent key has no position).
    auto at = [&](const char* k) { return node[k].IsDefined() ? node[k] : key; };
    if (!node["model"].IsDefined())
      fail(path + ".model", key, "missing 'model' (the registered model the parameters are for)");
    p.model = word(node["model"], path + ".model", true);
    p.description = word(node["description"], path + ".description", false);
    p.notes = word(node["notes"], path + ".notes", false);
    p.parameters = node["parameters"];
    parameters(p.parameters, path + ".parameters", at("parameters"));
    p.sources = sources(node["sources"], path + ".sources", at("sources"));
    check_coverage(p, path, node["sources"]);
    const YAML::Node cc = node["cross_checks"];
    if (cc.IsDefined() && !cc.IsNull()) {
      if (!cc.IsMap()) fail(path + ".cross_checks", cc, "expected a map of name: number, got " + kind_of(cc));
      check_keys(cc, path + ".cross_checks", {});
      for (auto it = cc.begin(); it != cc.end(); ++it) {
        double x = 0.0;
        const std::string k = it->first.as<std::string>();
        if (!scalar_number(it->second, x))
          fail(path + ".cross_checks." + k, it->second, "expected a number, got " + kind_of(it->second));
        p.cross_checks[k] = x;
      }
    }
    return p;
  }

  /// A map of scalars, with group sub-maps (eos:, failure:) of scalars one level deep.
  void parameters(const YAML::Node& n, const std::string& path, const YAML::Node& at) const {
    if (!n.IsMap() || n.size() == 0) fail(path, at, "expected a non-empty map of parameters, got " + kind_of(n));
    check_keys(n, path, {});
    for (auto it = n.begin(); it != n.end(); ++it) {
      const std::string k = path + "." + it->first.as<std::string>();
      const YAML::Node v = it->second;  // a copy (a handle): it-> yields a temporary
      if (v.IsMap()) {
        if (v.size() == 0) fail(k, it->first, "empty parameter group");
        check_keys(v, k, {});
        for (auto jt = v.begin(); jt != v.end(); ++jt)
          if (!jt->second.IsScalar())
            fail(k + "." + jt->first.as<std::string>(),
                 jt->second.IsDefined() && !jt->second.IsNull() ? jt->second : jt->first,
                 "expected a number or a word, got " + kind_of(jt->second));
      } else if (!v.IsScalar()) {
        fail(k, v.IsDefined() && !v.IsNull() ? v : it->first,
             "expected a number, a word or a group map, got " + kind_of(v));
      }
    }
  }

  std::vector<PresetSource> sources(const YAML::Node& n, const std::string& path, const YAML::Node& at) const {
    if (!n.IsSequence() || n.size() == 0)
      fail(path, at, "expected a non-empty list of sources (keys, cite, confidence), got " + kind_of(n));
    std::vector<PresetSource> out;
    const auto& levels = preset_confidence_levels();
    for (size_t i = 0; i < n.size(); ++i) {
      const YAML::Node s = n[i];
      const std::string sp = path + "." + std::to_string(i);
      if (!s.IsMap()) fail(sp, s, "expected a map (keys, cite, via, confidence), got " + kind_of(s));
      check_keys(s, sp, kSourceKeys);
      PresetSource src;
      const YAML::Node keys = s["keys"];
      if (!keys.IsSequence() || keys.size() == 0)
        fail(sp + ".keys", keys.IsDefined() ? keys : s,
             "expected a non-empty list of parameter keys, got " + kind_of(keys));
      for (size_t j = 0; j < keys.size(); ++j)
        src.keys.push_back(word(keys[j], sp + ".keys." + std::to_string(j), true));
      if (!s["cite"].IsDefined()) fail(sp + ".cite", s, "missing 'cite' (author, year, title, table)");
      src.cite = word(s["cite"], sp + ".cite", true);
      src.via = word(s["via"], sp + ".via", false);
      if (!s["confidence"].IsDefined())
        fail(sp + ".confidence", s, "missing 'confidence'; expected one of: " + join_names(levels));
      src.confidence = word(s["confidence"], sp + ".confidence", true);
      if (std::find(levels.begin(), levels.end(), src.confidence) == levels.end())
        fail(sp + ".confidence", s["confidence"],
             "unknown confidence '" + src.confidence + "'" + suggest(src.confidence, levels));
      if ((src.confidence == "checked" || src.confidence == "secondary") && src.via.empty())
        fail(sp + ".via", s,
             "confidence '" + src.confidence + "' needs 'via': where the numbers were compared or taken from");
      out.push_back(std::move(src));
    }
    return out;
  }

  /// Every parameter is listed under exactly one source, and every listed key names a parameter.
  /// `sources` is the preset's sources node (for positions in messages).
  void check_coverage(const MaterialPreset& p, const std::string& path, const YAML::Node& sources) const {
    const auto flat = flatten_parameters(p.parameters);
    std::map<std::string, int> covered;
    std::vector<std::string> names;
    for (const auto& [k, v] : flat) {
      covered[k] = 0;
      names.push_back(k);
    }
    for (size_t i = 0; i < p.sources.size(); ++i) {
      for (size_t j = 0; j < p.sources[i].keys.size(); ++j) {
        const std::string& key = p.sources[i].keys[j];
        // "eos.*" covers every key of the group eos.
        const bool group = key.size() > 2 && key.compare(key.size() - 2, 2, ".*") == 0;
        const std::string prefix = group ? key.substr(0, key.size() - 1) : std::string();
        int matched = 0;
        for (auto& [k, count] : covered)
          if (group ? k.compare(0, prefix.size(), prefix) == 0 : k == key) {
            ++count;
            ++matched;
          }
        if (matched == 0)
          fail(path + ".sources." + std::to_string(i) + ".keys." + std::to_string(j), sources[i]["keys"][j],
               "'" + key + "' names no parameter of this preset" + suggest(key, names));
      }
    }
    for (const auto& [k, v] : flat) {
      if (covered[k] == 1) continue;
      fail(path + ".parameters." + k, v,
           covered[k] == 0 ? "parameter '" + k + "' has no source: list it under the 'keys' of one entry of 'sources'"
                           : "parameter '" + k + "' is listed under " + std::to_string(covered[k]) +
                                 " sources; list it under exactly one");
    }
  }

  std::string file_;
  std::set<std::string> names_;
};

}  // namespace

const std::vector<std::string>& preset_confidence_levels() {
  static const std::vector<std::string> levels{"checked", "secondary", "recalled", "convention",
                                               "derived", "surrogate", "seed"};
  return levels;
}

std::string default_material_presets_path() {
  if (const char* env = std::getenv(kMaterialPresetsEnv); env && *env) return env;
  return (std::filesystem::path(data_dir()) / "data" / "materials.yaml").string();
}

MaterialPresetLibrary MaterialPresetLibrary::parse(const std::string& yaml_text, const std::string& file_name) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw DeckError(file_name, line_of(e.mark), column_of(e.mark), "", "YAML syntax error: " + e.msg);
  }
  MaterialPresetLibrary lib;
  lib.file_ = file_name;
  lib.presets_ = PresetParser(file_name).parse(root);
  return lib;
}

MaterialPresetLibrary MaterialPresetLibrary::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw Error("cannot read the material presets file '" + path + "' (set " + kMaterialPresetsEnv +
                " to the path of data/materials.yaml, or " + kDataDirEnv +
                " to the directory holding data/)");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), path);
}

MaterialPresetLibrary MaterialPresetLibrary::load_default() {
  return load(default_material_presets_path());
}

const MaterialPreset* MaterialPresetLibrary::find(const std::string& name) const {
  for (const auto& p : presets_)
    if (p.name == name) return &p;
  return nullptr;
}

const MaterialPreset& MaterialPresetLibrary::get(const std::string& name) const {
  if (const MaterialPreset* p = find(name)) return *p;
  throw Error("unknown material preset '" + name + "' (presets file " + file_ + ")" + suggest(name, names()));
}

std::vector<std::string> MaterialPresetLibrary::names() const {
  std::vector<std::string> out;
  for (const auto& p : presets_) out.push_back(p.name);
  return out;
}

std::vector<std::pair<std::string, YAML::Node>> flatten_parameters(const YAML::Node& parameters) {
  std::vector<std::pair<std::string, YAML::Node>> out;
  if (!parameters.IsMap()) return out;
  for (auto it = parameters.begin(); it != parameters.end(); ++it) {
    const std::string key = it->first.as<std::string>();
    if (it->second.IsMap()) {
      for (auto jt = it->second.begin(); jt != it->second.end(); ++jt)
        out.emplace_back(key + "." + jt->first.as<std::string>(), jt->second);
    } else {
      out.emplace_back(key, it->second);
    }
  }
  return out;
}

const std::vector<std::string>& elastic_parameter_keys() {
  static const std::vector<std::string> keys{"youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus"};
  return keys;
}

YAML::Node merge_preset_into(const MaterialPreset& preset, const YAML::Node& deck_material) {
  const std::string who = "material preset '" + preset.name + "'";
  const YAML::Node& deck = deck_material;  // const: operator[] must not insert keys into the deck
  if (deck.IsDefined() && !deck.IsNull() && !deck.IsMap())
    throw Error(who + ": expected the deck material to be a map, got " + kind_of(deck));
  const bool has_deck = deck.IsDefined() && deck.IsMap();
  auto deck_has = [&](const std::string& k) { return has_deck && deck[k].IsDefined() && !deck[k].IsNull(); };

  YAML::Node out(YAML::NodeType::Map);
  if (deck_has("model")) {
    const YAML::Node m = deck["model"];
    if (!m.IsScalar() || m.Scalar() != preset.model)
      throw Error(who + " is for model '" + preset.model + "', but the deck material gives model " + kind_of(m) +
                  " (drop 'model' or use a preset of that model)");
    out["model"] = m;
  } else {
    out["model"] = preset.model;
  }
  const auto& elastic = elastic_parameter_keys();
  bool deck_elastic = false;
  for (const auto& k : elastic) deck_elastic = deck_elastic || deck_has(k);

  for (auto it = preset.parameters.begin(); it != preset.parameters.end(); ++it) {
    const std::string key = it->first.as<std::string>();
    const YAML::Node value = it->second;  // a copy (a handle): it-> yields a temporary
    if (deck_elastic && std::find(elastic.begin(), elastic.end(), key) != elastic.end()) continue;
    if (value.IsMap()) {
      YAML::Node group(YAML::NodeType::Map);
      const YAML::Node d = has_deck ? deck[key] : YAML::Node();
      const bool deck_group = d.IsDefined() && !d.IsNull();
      if (deck_group && !d.IsMap())
        throw Error(who + ": '" + key + "' is a group of parameters (a map) in the preset, but the deck gives " +
                    kind_of(d));
      for (auto jt = value.begin(); jt != value.end(); ++jt) {
        const std::string sub = jt->first.as<std::string>();
        if (deck_group && d[sub].IsDefined()) continue;  // the deck's value, added below
        group[sub] = YAML::Clone(jt->second);
      }
      if (deck_group)
        for (auto jt = d.begin(); jt != d.end(); ++jt) group[jt->first.as<std::string>()] = jt->second;
      out[key] = group;
    } else if (!deck_has(key)) {
      out[key] = YAML::Clone(value);
    }
  }
  if (has_deck) {
    for (auto it = deck.begin(); it != deck.end(); ++it) {
      const std::string key = it->first.as<std::string>();
      if (key == "preset" || key == "model") continue;
      if (preset.parameters[key].IsDefined() && preset.parameters[key].IsMap()) continue;  // merged above
      out[key] = it->second;
    }
  }
  return out;
}

ParamValues preset_param_values(const MaterialPreset& preset, const std::vector<ParamSpec>& specs) {
  const std::string base = "presets." + preset.name + ".";
  auto fail = [&](const std::string& key, const YAML::Node& at, const std::string& message) {
    const YAML::Mark m = at.IsDefined() ? at.Mark() : YAML::Mark::null_mark();
    const int line = m.line >= 0 ? line_of(m) : preset.line;  // absent key: at the preset's name
    throw DeckError(preset.file, line, column_of(m), base + key,
                    "material preset '" + preset.name + "' (" + preset.model + "): " + message);
  };
  std::vector<std::string> names;
  for (const auto& s : specs) names.push_back(s.name);
  const auto flat = flatten_parameters(preset.parameters);
  std::map<std::string, YAML::Node> given;
  for (const auto& [k, v] : flat) {
    if (std::find(names.begin(), names.end(), k) == names.end())
      fail(k, v, "'" + k + "' is not a parameter of model '" + preset.model + "'" + suggest(k, names));
    given[k] = v;
  }
  ParamValues values;
  for (const ParamSpec& s : specs) {
    const auto it = given.find(s.name);
    if (!s.choices.empty()) {
      if (it == given.end()) {
        values.choices[s.name] = s.default_choice;
        continue;
      }
      const std::string w = it->second.Scalar();
      if (std::find(s.choices.begin(), s.choices.end(), w) == s.choices.end())
        fail(s.name, it->second, "expected one of " + join_names(s.choices) + ", got '" + w + "'");
      values.choices[s.name] = w;
      continue;
    }
    if (it == given.end()) {
      if (s.required) fail(s.name, YAML::Node(), "missing required parameter '" + s.name + "' (" + s.description + ")");
      values[s.name] = s.default_value;
      continue;
    }
    double x = 0.0;
    if (!scalar_number(it->second, x)) fail(s.name, it->second, "expected a number, got " + kind_of(it->second));
    const NumberRange range{s.min, s.max, s.min_exclusive, s.max_exclusive, s.unit};
    if (!range.contains(x)) fail(s.name, it->second, "expected " + range.describe() + ", got " + format_number(x));
    values[s.name] = x;
  }
  return values;
}

}  // namespace ballista
