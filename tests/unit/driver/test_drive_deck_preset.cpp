// `preset:` in a deck material (deck/material_reader): the preset's parameters from
// data/materials.yaml under the deck's own keys.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "deck/material_presets.hpp"
#include "driver/drive_deck.hpp"

namespace test_drive_deck_preset {

using namespace ballista;

namespace {

std::string deck(const std::string& material_body) {
  return "materials:\n  cu:\n" + material_body +
         "drive:\n  legs:\n    - {duration: 1.0e-3, steps: 10, strain: {11: -0.01}}\n";
}

TEST(DeckPreset, PresetParametersWithDeckOverrides) {
  const auto lib = MaterialPresetLibrary::load_default();
  const MaterialPreset& cu = lib.get("copper_ofhc_jc");
  const ParamValues expect = preset_param_values(cu, find_material(cu.model)->params);
  const DriveDeck d = parse_drive_deck(deck("    preset: copper_ofhc_jc\n    jc_a: 1.0e8\n    eos: {min_pressure: -1.0e9}\n"),
                                       "preset.yaml");
  EXPECT_EQ(d.material.model, cu.model);
  for (const auto& [k, v] : expect) {
    if (k == "jc_a" || k == "eos.min_pressure" || std::isnan(v)) continue;
    EXPECT_EQ(d.material.params.at(k), v) << k;  // untouched keys come from the preset exactly
  }
  EXPECT_EQ(d.material.params.at("jc_a"), 1.0e8);             // the deck wins
  EXPECT_EQ(d.material.params.at("eos.min_pressure"), -1.0e9);  // group merged key by key
  EXPECT_EQ(d.material.params.choices.at("eos.type"), expect.choices.at("eos.type"));
}

TEST(DeckPreset, UnknownPresetNamesTheKeyAndLine) {
  try {
    (void)parse_drive_deck(deck("    preset: copper_ofhc_j\n"), "preset.yaml");
    FAIL() << "expected a DeckError";
  } catch (const DeckError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("preset.yaml:3"), std::string::npos) << msg;
    EXPECT_NE(msg.find("materials.cu.preset"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'copper_ofhc_jc'"), std::string::npos) << msg;
  }
}

TEST(DeckPreset, ModelMismatchIsAnError) {
  EXPECT_THROW((void)parse_drive_deck(deck("    preset: copper_ofhc_jc\n    model: j2_plasticity\n"), "preset.yaml"),
               DeckError);
}

}  // namespace

}  // namespace test_drive_deck_preset
