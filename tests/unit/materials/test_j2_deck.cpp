// The J2-family parameters as a user writes them in a deck (docs/deck.md, docs/materials.md):
// hardening laws, kinematic hardening, the eos sub-map and johnson_cook parse, resolve to
// themselves, and bad combinations are reported at the key with file, line and message.
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "material_driver.hpp"

namespace test_j2_deck {

using namespace ballista;

namespace {

/// A small axisymmetric Taylor-bar deck (examples/taylor_bar_mpm.yaml) with the given material
/// block (indented under `materials:`).
std::string deck(const std::string& material) {
  return "simulation: {solver: mpm, dimension: axisymmetric, end_time: 1.0e-6}\n"
         "materials:\n" +
         material +
         "grid: {lower: [0, 0], upper: [10.0e-3, 34.0e-3], cell_size: 1.0e-3,\n"
         "       boundary: {x_min: symmetry, y_min: wall}}\n"
         "bodies:\n"
         "  - {name: bar, material: m, shape: {type: cylinder, center: [0, 0, 0], axis: y, radius: 3.2e-3, "
         "length: 32.4e-3}, velocity: [0, -227.0, 0]}\n";
}

std::string body_of(const std::string& resolved) { return resolved.substr(resolved.find('\n') + 1); }

const char* kVoceKinematicMg =
    "  m:\n"
    "    model: j2_plasticity\n"
    "    density: 8930\n"
    "    youngs_modulus: 117.0e9\n"
    "    poisson_ratio: 0.35\n"
    "    yield_stress: 120.0e6\n"
    "    hardening_law: voce\n"
    "    hardening_modulus: 0.5e9\n"
    "    saturation_stress: 150.0e6\n"
    "    saturation_rate: 10\n"
    "    kinematic_modulus: 2.0e9\n"
    "    eos: {type: mie_gruneisen, sound_speed: 3940, hugoniot_slope: 1.489, gruneisen_gamma: 2.02}\n";

const char* kJohnsonCook =
    "  m:\n"
    "    model: johnson_cook\n"
    "    density: 8960\n"
    "    bulk_modulus: 139.1e9\n"
    "    shear_modulus: 47.7e9\n"
    "    jc_a: 90.0e6\n"
    "    jc_b: 292.0e6\n"
    "    jc_n: 0.31\n"
    "    jc_c: 0.025\n"
    "    jc_m: 1.09\n"
    "    melt_temperature: 1356\n"
    "    specific_heat: 383\n"
    "    eos: {type: mie_gruneisen, sound_speed: 3940, hugoniot_slope: 1.489, gruneisen_gamma: 2.02}\n";

/// The DeckError of a deck, or a failure if it parses.
DeckError deck_error(const std::string& text) {
  try {
    parse_deck(text, "bad.yaml");
  } catch (const DeckError& e) {
    return e;
  }
  ADD_FAILURE() << "deck accepted:\n" << text;
  return DeckError("", 0, 0, "", "");
}

}  // namespace

TEST(J2Deck, VoceKinematicMieGruneisenParsesAndResolvesToItself) {
  const Scenario s = parse_deck(deck(kVoceKinematicMg), "voce.yaml");
  ASSERT_EQ(s.materials.size(), 1u);
  const MaterialSpec& m = s.materials[0];
  EXPECT_EQ(m.params.choice("hardening_law"), "voce");
  EXPECT_EQ(m.params.choice("eos.type"), "mie_gruneisen");
  EXPECT_EQ(m.params.at("kinematic_modulus"), 2e9);
  EXPECT_TRUE(std::isnan(m.params.at("hardening_exponent")));  // not given
  const auto mat = find_material(m.model)->create(m.name, m.params);
  EXPECT_EQ(mat->state_fields().size(), 8u);  // eqps, 6 backstress, energy_density
  const Scenario again = parse_deck(s.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(body_of(again.resolved_yaml), body_of(s.resolved_yaml));
}

TEST(J2Deck, JohnsonCookParsesAndResolvesToItself) {
  const Scenario s = parse_deck(deck(kJohnsonCook), "jc.yaml");
  const MaterialSpec& m = s.materials.at(0);
  EXPECT_EQ(m.params.at("taylor_quinney"), 0.9);            // default
  EXPECT_EQ(m.params.at("reference_temperature"), 294.0);   // default
  EXPECT_EQ(m.params.at("reference_strain_rate"), 1.0);     // default
  EXPECT_TRUE(std::isnan(m.params.at("initial_temperature")));  // default: the reference temperature
  EXPECT_NO_THROW(find_material(m.model)->create(m.name, m.params));
  const Scenario again = parse_deck(s.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(body_of(again.resolved_yaml), body_of(s.resolved_yaml));
}

// Errors name the file, the key and what was expected.
TEST(J2Deck, BadCombinationsAreReportedAtTheKey) {
  // power_law without its exponent: reported at the material's map (the key is absent).
  std::string text = deck(
      "  m: {model: j2_plasticity, density: 7800, bulk_modulus: 160e9, shear_modulus: 80e9, yield_stress: 3e8,\n"
      "      hardening_law: power_law, hardening_coefficient: 5e8}\n");
  DeckError e = deck_error(text);
  EXPECT_EQ(e.file(), "bad.yaml");
  EXPECT_NE(std::string(e.what()).find("hardening_exponent is required when hardening_law is power_law"),
            std::string::npos)
      << e.what();
  // A Voce key under the linear law: reported at that key's line.
  text = deck(
      "  m:\n"
      "    model: j2_plasticity\n"
      "    density: 7800\n"
      "    bulk_modulus: 160e9\n"
      "    shear_modulus: 80e9\n"
      "    yield_stress: 3e8\n"
      "    saturation_stress: 1e8\n");
  e = deck_error(text);
  EXPECT_EQ(e.line(), 9);  // simulation, materials, m, model, density, bulk, shear, yield, saturation
  EXPECT_NE(e.key_path().find("saturation_stress"), std::string::npos) << e.key_path();
  EXPECT_NE(std::string(e.what()).find("not used by hardening_law linear"), std::string::npos) << e.what();
  // An unknown law lists the choices.
  text = deck(
      "  m: {model: j2_plasticity, density: 7800, bulk_modulus: 160e9, shear_modulus: 80e9, yield_stress: 3e8,\n"
      "      hardening_law: swift}\n");
  e = deck_error(text);
  EXPECT_NE(std::string(e.what()).find("power_law"), std::string::npos) << e.what();
  // Johnson-Cook: melt below the reference temperature, at the key.
  std::string jc = kJohnsonCook;
  jc.replace(jc.find("melt_temperature: 1356"), 22, "melt_temperature: 250");
  e = deck_error(deck(jc));
  EXPECT_NE(e.key_path().find("melt_temperature"), std::string::npos) << e.key_path();
  EXPECT_NE(std::string(e.what()).find("must exceed reference_temperature"), std::string::npos) << e.what();
  // Out-of-range Taylor-Quinney coefficient: the deck range check.
  jc = kJohnsonCook;
  jc += "    taylor_quinney: 1.2\n";
  e = deck_error(deck(jc));
  EXPECT_NE(e.key_path().find("taylor_quinney"), std::string::npos) << e.key_path();
}

}  // namespace test_j2_deck
