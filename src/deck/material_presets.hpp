#pragma once
// Material presets: named, cited parameter sets (data/materials.yaml, docs/material_data.md).
//
// A preset holds the parameters of one material exactly as a deck material would give them
// (numbers and words at the top level, the eos:/failure: groups as sub-maps), the model they are
// for, and the source of every value. A deck material can name a preset and override any of its
// keys (merge_preset_into); the result is read like any other deck material.
//
// The file is validated when it is loaded: every problem is a DeckError naming the presets file,
// the line and the key path (presets.<name>.<key>), so a data-entry slip is reported where it is.
#include <map>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "materials/material.hpp"

namespace ballista {

/// Where one group of a preset's values comes from.
struct PresetSource {
  std::vector<std::string> keys;  ///< parameter keys it covers ("eos.sound_speed"; "eos.*" = group)
  std::string cite;               ///< the publication (author, year, title, table)
  std::string via;                ///< where the numbers were compared / taken from ("" if none)
  std::string confidence;         ///< one of preset_confidence_levels()
};

struct MaterialPreset {
  std::string name;
  std::string model;        ///< registered model name (find_material)
  std::string description;  ///< one line
  /// A map: deck keys -> scalars, and group -> map of scalars. yaml-cpp nodes have reference
  /// semantics: a copy of a MaterialPreset shares this node, and `copy.parameters = other` would
  /// overwrite the shared data; rebind with `copy.parameters.reset(other)` or edit a YAML::Clone.
  YAML::Node parameters;
  std::vector<PresetSource> sources;
  std::map<std::string, double> cross_checks;  ///< same quantities from independent sources
  std::string notes;
  std::string file;  ///< the presets file it was read from (for messages)
  int line = 0;      ///< 1-based line of the preset's name in that file
};

/// checked, secondary, recalled, convention, derived, surrogate, seed (meanings in
/// data/materials.yaml and docs/material_data.md).
const std::vector<std::string>& preset_confidence_levels();

/// Environment variable naming a presets file that replaces the default one.
inline constexpr const char* kMaterialPresetsEnv = "BALLISTA_MATERIALS_FILE";

/// $BALLISTA_MATERIALS_FILE if set and non-empty, else <data_dir()>/data/materials.yaml
/// (core/data_dir.hpp: the installed share/ballista, or the source tree of a build).
std::string default_material_presets_path();

class MaterialPresetLibrary {
 public:
  /// Reads and validates a presets file; throws DeckError (file, line, key path) on bad data and
  /// Error if the file cannot be read.
  static MaterialPresetLibrary load(const std::string& path);
  /// Same from text; `file_name` is used in messages.
  static MaterialPresetLibrary parse(const std::string& yaml_text, const std::string& file_name);
  /// load(default_material_presets_path()).
  static MaterialPresetLibrary load_default();

  /// nullptr if there is no preset of that name.
  const MaterialPreset* find(const std::string& name) const;
  /// The preset `name`; throws Error naming the file and the closest preset name otherwise.
  const MaterialPreset& get(const std::string& name) const;
  /// Preset names in file order.
  std::vector<std::string> names() const;
  const std::vector<MaterialPreset>& presets() const { return presets_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<MaterialPreset> presets_;
};

/// The parameter keys of a parameters map in flat (dotted) form, with their values:
/// {density: 1, eos: {sound_speed: 2}} -> {"density": 1, "eos.sound_speed": 2}. The order is the
/// map order. Values are the original nodes (positions preserved).
std::vector<std::pair<std::string, YAML::Node>> flatten_parameters(const YAML::Node& parameters);

/// The elastic-constant keys; a deck that sets any of them replaces the preset's pair as a whole
/// (merging a preset's (E, nu) with a deck's (K, G) would give the model both pairs).
const std::vector<std::string>& elastic_parameter_keys();

/// A deck material with its preset applied: `deck_material` is the material's map from the deck
/// (it may contain the key `preset`, which is dropped, and `model`, which must then equal the
/// preset's). The result holds the preset's model and parameters with every key the deck sets
/// taking precedence, group maps (eos:, failure:) merged key by key; the elastic pair is replaced
/// as a whole if the deck sets any elastic constant. Deck nodes are kept as they are (so their
/// positions still point into the deck); preset nodes are copies. Throws Error if the deck's
/// model differs from the preset's or a group is not a map on either side.
YAML::Node merge_preset_into(const MaterialPreset& preset, const YAML::Node& deck_material);

/// The preset's parameters as ParamValues for a model with these specs, as the deck reader would
/// build them: numbers range-checked, words checked against their choices, defaults filled in.
/// Throws DeckError (presets file, line, presets.<name>.<key>) for an unknown key, a word where a
/// number is expected (or the reverse), a value out of range or a missing required parameter.
ParamValues preset_param_values(const MaterialPreset& preset, const std::vector<ParamSpec>& specs);

}  // namespace ballista
