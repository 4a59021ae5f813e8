// A deck material with `preset:` read the way `ballista run` reads it (read_deck on a file, with a
// --set override): the presets file is loaded and merged into the deck (deck/material_presets.cpp).
// The reference values are read from data/materials.yaml with plain yaml-cpp, not through Ballista.
// Under AddressSanitizer (make test-sanitize) this is also the regression test of a
// stack-use-after-scope: the preset parser and the merge once bound `const YAML::Node&` to
// `it->second` of a yaml-cpp iterator, a member of a temporary proxy that dies at the end of the
// statement.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "deck/deck_reader.hpp"

namespace test_deck_preset_run_path {

using namespace ballista;

namespace {

const std::filesystem::path kSource(BALLISTA_SOURCE_DIR);

const MaterialSpec& material(const Scenario& s, const std::string& name) {
  for (const auto& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material '" + name + "' in the scenario");
}

}  // namespace

TEST(DeckPresetRunPath, ExampleDeckWithPresetAndOverrideResolvesToThePresetValues) {
  const YAML::Node file = YAML::LoadFile((kSource / "data" / "materials.yaml").string());
  const YAML::Node preset = file["presets"]["copper_ofhc_jc"];
  ASSERT_TRUE(preset.IsMap());

  const Scenario s = read_deck((kSource / "examples" / "taylor_bar_jc_mpm.yaml").string(),
                               {"materials.copper.jc_b=3.0e8", "materials.copper.eos.gruneisen_gamma=2.0"});
  const MaterialSpec& cu = material(s, "copper");
  EXPECT_EQ(cu.model, preset["model"].as<std::string>());

  // Every top-level number of the preset, except the one overridden, arrives unchanged.
  int checked = 0;
  for (const auto& kv : preset["parameters"]) {
    const std::string key = kv.first.as<std::string>();
    if (kv.second.IsMap() || key == "jc_b") continue;
    EXPECT_EQ(cu.params.at(key), kv.second.as<double>()) << key;
    ++checked;
  }
  EXPECT_EQ(checked, 13);  // density ... taylor_quinney in data/materials.yaml
  EXPECT_EQ(cu.params.at("jc_b"), 3.0e8);  // --set wins over the preset

  // Groups merge key by key: the override replaces one EOS key, the others stay the preset's.
  EXPECT_EQ(cu.params.at("eos.gruneisen_gamma"), 2.0);
  EXPECT_EQ(cu.params.at("eos.sound_speed"), preset["parameters"]["eos"]["sound_speed"].as<double>());
  EXPECT_EQ(cu.params.at("eos.hugoniot_slope"), preset["parameters"]["eos"]["hugoniot_slope"].as<double>());
  EXPECT_EQ(cu.params.choices.at("eos.type"), "mie_gruneisen");
  // The deck's failure group (criterion, erosion) over the preset's damage constants.
  EXPECT_EQ(cu.params.choices.at("failure.erosion"), "zero_stress");
  EXPECT_EQ(cu.params.at("failure.d3"), preset["parameters"]["failure"]["d3"].as<double>());
}

}  // namespace test_deck_preset_run_path
