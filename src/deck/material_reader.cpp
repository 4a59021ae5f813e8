#include "deck/material_reader.hpp"

#include <climits>
#include <cmath>
#include <map>
#include <set>

#include "deck/material_presets.hpp"

namespace ballista {

namespace {

/// `preset: NAME` in a deck material: the preset's model and parameters (data/materials.yaml,
/// docs/material_data.md) under the deck's own keys, which win. The deck's YAML is rewritten in
/// place, so every later error still points at the deck's own line for keys the deck sets.
void apply_preset(DeckNode& ms, const std::string& name) {
  YAML::Node materials = ms.yaml();  // shares the deck document (yaml-cpp reference semantics)
  YAML::Node mat = materials[name];
  if (!mat.IsMap() || !mat["preset"]) return;
  static const MaterialPresetLibrary library = MaterialPresetLibrary::load_default();
  DeckNode m = ms.entry(name);
  // The merge below rebuilds the map: a duplicate key must be caught before it disappears.
  std::set<std::string> seen;
  for (auto it = mat.begin(); it != mat.end(); ++it)
    if (it->first.IsScalar() && !seen.insert(it->first.Scalar()).second)
      m.fail(it->first.Scalar(), "duplicate key '" + shorten(it->first.Scalar()) + "' in materials." + name);
  const std::string preset_name = m.string("preset");
  const MaterialPreset* preset = library.find(preset_name);
  if (!preset) {
    std::string hint;
    if (const std::string best = closest_name(preset_name, library.names()); !best.empty())
      hint = "; did you mean '" + best + "'?";
    m.fail("preset", "unknown material preset '" + preset_name + "'" + hint + " (presets in " + library.file() +
                         ": " + join_names(library.names()) + ")");
  }
  try {
    materials[name] = merge_preset_into(*preset, mat);
  } catch (const Error& e) {
    m.fail("preset", e.what());
  }
}

}  // namespace

void read_param(DeckNode& n, const std::string& key, const ParamSpec& p, ParamValues& out,
                std::map<std::string, DeckMark>& marks) {
  if (n.has(key)) marks[p.name] = n.mark_of(key);
  if (!p.choices.empty()) {
    out.choices[p.name] = n.choice(key, p.default_choice, p.choices);
    return;
  }
  if (p.integer) {
    const long lo = std::isinf(p.min) ? LONG_MIN : static_cast<long>(p.min);
    const long hi = std::isinf(p.max) ? LONG_MAX : static_cast<long>(p.max);
    out[p.name] = static_cast<double>(p.required ? n.integer(key, lo, hi)
                                                 : n.integer(key, static_cast<long>(p.default_value), lo, hi));
    return;
  }
  const NumberRange range{p.min, p.max, p.min_exclusive, p.max_exclusive, p.unit};
  double v = 0.0;
  if (p.required) {
    v = n.number(key, range);
  } else if (std::isnan(p.default_value)) {
    const auto given = n.optional_number(key, range);
    v = given ? *given : p.default_value;
    if (!given) n.set_resolved(key, YAML::Node(YAML::NodeType::Null));
  } else {
    v = n.number(key, p.default_value, range);
  }
  out[p.name] = v;
}

MaterialSpec read_material_spec(DeckNode& ms, const std::string& name) {
  apply_preset(ms, name);
  DeckNode m = ms.entry(name);
  MaterialSpec spec;
  spec.name = name;
  spec.mark = m.mark();
  std::vector<std::string> models;
  for (const auto& f : material_registry()) models.push_back(f.model);
  spec.model = m.string("model");
  const MaterialFactory* factory = find_material(spec.model);
  if (!factory) {
    std::string hint;
    if (const std::string best = closest_name(spec.model, models); !best.empty())
      hint = "; did you mean '" + best + "'?";
    m.fail("model",
           "unknown material model '" + spec.model + "'" + hint + " (registered models: " + join_names(models) + ")");
  }
  // Parameters named "group.key" live in a sub-map of the material (eos: {...}).
  std::map<std::string, DeckNode> groups;
  auto node_of = [&](const std::string& param, std::string& key) -> DeckNode& {
    const auto dot = param.find('.');
    if (dot == std::string::npos) {
      key = param;
      return m;
    }
    key = param.substr(dot + 1);
    const std::string group = param.substr(0, dot);
    auto it = groups.find(group);
    if (it == groups.end()) it = groups.emplace(group, m.map(group, false)).first;
    return it->second;
  };
  for (const ParamSpec& p : factory->params) {
    std::string key;
    DeckNode& n = node_of(p.name, key);
    read_param(n, key, p, spec.params, spec.param_marks);
  }
  for (auto& [group, n] : groups) n.finish();
  m.finish();
  // Cross-checks of the model (e.g. exactly one pair of elastic constants).
  try {
    (void)factory->create(name, spec.params);
  } catch (const ParamError& e) {
    const std::string msg = "material '" + name + "' (" + spec.model + "): " + e.what();
    std::string key;
    node_of(e.param(), key).fail(key, msg);  // at the parameter, or at its map if it is absent
  } catch (const DeckError&) {
    throw;
  } catch (const std::exception& e) {
    m.fail("material '" + name + "' (" + spec.model + "): " + e.what());
  }
  return spec;
}

}  // namespace ballista
