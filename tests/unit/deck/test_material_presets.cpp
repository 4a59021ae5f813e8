// Material presets (data/materials.yaml, docs/material_data.md): the file parses, every value has a
// source, the numbers are SI-plausible and pass physics cross-checks that catch data-entry slips
// (a wrong exponent, MPa typed as Pa, swapped columns), presets of registered models construct,
// and deck keys override preset keys when a preset is merged into a deck material.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "deck/material_presets.hpp"
#include "materials/explosive_eos.hpp"
#include "materials/material.hpp"
#include "support/test_files.hpp"
#include "unit/materials/material_driver.hpp"

namespace test_material_presets {

using namespace ballista;

namespace {

std::string presets_path() {
  return (std::filesystem::path(BALLISTA_SOURCE_DIR) / "data" / "materials.yaml").string();
}

const MaterialPresetLibrary& library() {
  static const MaterialPresetLibrary lib = MaterialPresetLibrary::load(presets_path());
  return lib;
}

/// The number `key` ("density", "eos.sound_speed") of a preset, NaN if absent or not a number.
double num(const MaterialPreset& p, const std::string& key) {
  for (const auto& [k, v] : flatten_parameters(p.parameters))
    if (k == key) {
      try {
        return v.as<double>();
      } catch (const YAML::Exception&) {
        return NAN;
      }
    }
  return NAN;
}

std::string word(const MaterialPreset& p, const std::string& key) {
  for (const auto& [k, v] : flatten_parameters(p.parameters))
    if (k == key) return v.Scalar();
  return {};
}

bool has(const MaterialPreset& p, const std::string& key) {
  for (const auto& [k, v] : flatten_parameters(p.parameters))
    if (k == key) return true;
  return false;
}

/// K and G of a preset from whichever pair it gives (standard isotropic relations).
struct Elastic {
  double K = NAN, G = NAN, E = NAN, nu = NAN;
};
Elastic elastic(const MaterialPreset& p) {
  Elastic e;
  if (has(p, "youngs_modulus")) {
    e.E = num(p, "youngs_modulus");
    e.nu = num(p, "poisson_ratio");
    e.K = e.E / (3.0 * (1.0 - 2.0 * e.nu));
    e.G = e.E / (2.0 * (1.0 + e.nu));
  } else if (has(p, "bulk_modulus")) {
    e.K = num(p, "bulk_modulus");
    e.G = num(p, "shear_modulus");
    e.E = 9.0 * e.K * e.G / (3.0 * e.K + e.G);
    e.nu = (3.0 * e.K - 2.0 * e.G) / (2.0 * (3.0 * e.K + e.G));
  }
  return e;
}

// Parameter names of the models that are specified (issue 3 brief) but not registered on this
// branch; once a model is registered its own ParamSpecs are used instead (test below).
const std::set<std::string> kEosKeys{"eos.type", "eos.sound_speed", "eos.hugoniot_slope", "eos.gruneisen_gamma",
                                     "eos.min_pressure"};
const std::set<std::string> kElasticKeys{"density", "youngs_modulus", "poisson_ratio", "bulk_modulus", "shear_modulus"};
std::set<std::string> johnson_cook_keys() {
  std::set<std::string> k = kElasticKeys;
  for (const char* n : {"jc_a",
                        "jc_b",
                        "jc_n",
                        "jc_c",
                        "jc_m",
                        "reference_strain_rate",
                        "reference_temperature",
                        "melt_temperature",
                        "initial_temperature",
                        "specific_heat",
                        "taylor_quinney",
                        "failure.criterion",
                        "failure.erosion",
                        "failure.d1",
                        "failure.d2",
                        "failure.d3",
                        "failure.d4",
                        "failure.d5",
                        "failure.reference_strain_rate",
                        "failure.max_stress",
                        "failure.critical_porosity",
                        "failure.fracture_strain",
                        "failure.initial_porosity"})
    k.insert(n);
  k.insert(kEosKeys.begin(), kEosKeys.end());
  return k;
}
// The geomodel's deck keys (docs/materials.md, "geomodel").
std::set<std::string> geomodel_keys() {
  return {"density",
          "bulk_modulus",
          "bulk_modulus_gain",
          "bulk_modulus_i1_scale",
          "shear_modulus",
          "poisson_ratio_low",
          "poisson_ratio_gain",
          "peak_i1",
          "fslope",
          "stren",
          "yslope",
          "cap_ratio",
          "crush_p0",
          "crush_p1",
          "crush_p3",
          "cap_evolution",
          "flow_beta",
          "fluid_bulk_modulus",
          "initial_pore_pressure",
          "matrix_bulk_modulus",
          "relaxation_time",
          "relaxation_rate_exponent",
          "max_substeps"};
}
std::set<std::string> water_keys() {
  std::set<std::string> k{"density", "bulk_modulus"};
  k.insert(kEosKeys.begin(), kEosKeys.end());
  return k;
}
const std::map<std::string, std::set<std::string>> kWordChoices{
    {"eos.type", {"linear", "mie_gruneisen"}},
    {"failure.criterion", {"none", "johnson_cook_damage", "melt", "tepla", "drucker_stability", "max_stress"}},
    {"failure.erosion", {"none", "allow_no_tension", "allow_no_shear", "zero_stress"}},
    {"hardening_law", {"linear", "power_law", "voce"}},
    {"products", {"jwl", "ideal_gas"}},
    {"cap_evolution", {"crush_curve", "fixed"}}};

}  // namespace

// ---- the data file ---------------------------------------------------------------------------

TEST(MaterialPresets, FileParsesAndHoldsTheSeedMetals) {
  const auto& lib = library();
  for (const char* name : {"copper_ofhc_jc", "tungsten_alloy_jc", "steel_4340_jc", "steel_4130_jc", "steel_1018_jc",
                           "aluminium_2024_t351_jc", "aluminium_6061_t6_jc", "copper_taylor_b6_j2", "water"}) {
    const MaterialPreset* p = lib.find(name);
    ASSERT_NE(p, nullptr) << name;
    EXPECT_EQ(p->name, name);
    EXPECT_GT(p->line, 0) << name;
    EXPECT_EQ(p->file, presets_path());
  }
  EXPECT_EQ(lib.names().size(), lib.presets().size());
  EXPECT_EQ(lib.find("no_such_material"), nullptr);
  try {
    (void)lib.get("copper_ofhc");
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'copper_ofhc_jc'"), std::string::npos) << e.what();
  }
}

TEST(MaterialPresets, EveryPresetHasAModelSourcesAndKnownKeys) {
  const std::map<std::string, std::set<std::string>> unregistered{
      {"johnson_cook", johnson_cook_keys()}, {"water", water_keys()}, {"geomodel", geomodel_keys()}};
  for (const auto& p : library().presets()) {
    SCOPED_TRACE(p.name);
    EXPECT_FALSE(p.model.empty());
    EXPECT_FALSE(p.description.empty());
    ASSERT_FALSE(p.sources.empty());
    for (const auto& s : p.sources) {
      EXPECT_GE(s.cite.size(), 10u) << "a citation, not a placeholder";
      EXPECT_FALSE(s.keys.empty());
    }
    // Words are valid choices, wherever they appear.
    for (const auto& [k, v] : flatten_parameters(p.parameters)) {
      const auto c = kWordChoices.find(k);
      if (c != kWordChoices.end()) {
        EXPECT_TRUE(c->second.count(v.Scalar())) << k << " = " << v.Scalar();
      }
    }
    if (find_material(p.model)) continue;  // checked against the model's own specs below
    const auto it = unregistered.find(p.model);
    ASSERT_NE(it, unregistered.end()) << "model '" << p.model << "' is neither registered nor specified";
    for (const auto& [k, v] : flatten_parameters(p.parameters)) EXPECT_TRUE(it->second.count(k)) << k;
  }
}

// Order-of-magnitude bounds for metals, water and rocks in SI units. Each is wide enough for every
// engineering metal (and porous rock, for the geomodel keys) and narrow enough that a unit slip
// (MPa typed as Pa: 1e6 too small; GPa as MPa: 1e3 too small; g/cm^3 as kg/m^3: 1e3 too small;
// Celsius for Kelvin) falls outside. Geomodel signs: tension positive, so crush_p0 < 0.
TEST(MaterialPresets, ValuesAreSIPlausible) {
  const std::map<std::string, std::pair<double, double>> bounds{
      {"density", {500.0, 25000.0}},       // kg/m^3: lithium .. osmium
      {"youngs_modulus", {10e9, 500e9}},   // Pa
      {"bulk_modulus", {1e9, 500e9}},      // Pa (water 2.2 GPa .. tungsten 310 GPa)
      {"shear_modulus", {5e9, 250e9}},     // Pa
      {"poisson_ratio", {0.2, 0.45}},      // metals
      {"yield_stress", {1e6, 5e9}},        // Pa
      {"hardening_modulus", {0.0, 50e9}},  // Pa
      {"jc_a", {1e6, 5e9}},                // Pa
      {"jc_b", {1e6, 5e9}},                // Pa
      {"jc_n", {0.01, 1.0}},
      {"jc_c", {0.0, 0.2}},
      {"jc_m", {0.1, 3.0}},
      {"reference_strain_rate", {1e-6, 1e3}},     // 1/s
      {"reference_temperature", {200.0, 400.0}},  // K: room temperature
      {"initial_temperature", {200.0, 400.0}},    // K
      {"melt_temperature", {500.0, 4000.0}},      // K
      {"specific_heat", {100.0, 5000.0}},         // J/(kg K): tungsten 134 .. water 4190
      {"taylor_quinney", {0.5, 1.0}},
      {"eos.sound_speed", {1000.0, 8000.0}},  // m/s
      {"eos.hugoniot_slope", {0.8, 2.6}},
      {"eos.gruneisen_gamma", {0.05, 3.5}},
      {"failure.reference_strain_rate", {1e-6, 1e3}},
      {"failure.d1", {-5.0, 5.0}},
      {"failure.d2", {0.0, 10.0}},
      {"failure.d3", {-10.0, 0.0}},
      {"failure.d4", {-0.1, 0.1}},
      {"failure.d5", {0.0, 5.0}},
      // geomodel (rocks): PEAKI1 = I1 of the tensile vertex, a few MPa .. tens of MPa for rocks
      {"peak_i1", {1e5, 1e9}},                // Pa
      {"fslope", {0.0, 2.0}},                 // d sqrt(J2) / d(-I1)
      {"stren", {1e6, 5e9}},                  // Pa
      {"yslope", {0.0, 1.0}},                 //
      {"cap_ratio", {0.1, 20.0}},             // Kayenta decks use 0.5 .. 6
      {"crush_p0", {-2e10, -1e6}},            // Pa, I1 of the cap: compression, negative
      {"crush_p1", {1e-12, 1e-6}},            // 1/Pa
      {"crush_p3", {1e-3, 2.0}},              // -ln(1 - phi0): porosity 0.1 % .. 86 %
      {"fluid_bulk_modulus", {1e8, 1e10}},    // Pa: gas-laden .. glycerol-like liquids; water 2.2 GPa
      {"initial_pore_pressure", {0.0, 3e8}},  // Pa: ambient .. deep reservoir
      {"matrix_bulk_modulus", {1e9, 500e9}},  // Pa: grain moduli (quartz 37 GPa)
      // explosives (Dobratz & Crawford 1985 tables span these)
      {"detonation_speed", {4000.0, 10000.0}},  // m/s
      {"cj_pressure", {5e9, 50e9}},             // Pa
      {"jwl.a", {1e11, 2e12}},                  // Pa
      {"jwl.b", {1e9, 1e11}},                   // Pa
      {"jwl.r1", {3.0, 7.0}},
      {"jwl.r2", {0.5, 2.5}},
      {"jwl.omega", {0.2, 0.5}},
      {"detonation_energy", {2e9, 15e9}},       // J/m^3
  };
  int checked = 0;
  for (const auto& p : library().presets()) {
    SCOPED_TRACE(p.name);
    for (const auto& [k, v] : flatten_parameters(p.parameters)) {
      if (kWordChoices.count(k)) continue;
      const auto b = bounds.find(k);
      ASSERT_NE(b, bounds.end()) << "no plausibility bound for '" << k << "': add one";
      const double x = num(p, k);
      ASSERT_TRUE(std::isfinite(x)) << k << " is not a number";
      EXPECT_GE(x, b->second.first) << k;
      EXPECT_LE(x, b->second.second) << k;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

// sqrt(K/rho) from the elastic constants against the Hugoniot intercept C0 of the Mie-Gruneisen
// EOS (Meyers 1994 ch. 4: C0 approximates the bulk sound speed). They are not the same number:
// C0 is a straight-line fit to Us-up data over a finite range (curvature near up = 0 moves it by a
// few %), and handbook K (from E, nu) may be isothermal while C0 is adiabatic (K_S/K_T = 1 + alpha
// Gamma T, 1-2 % for metals at room temperature). Measured here: -4.6 % at worst (aluminium 2024,
// 6061); 10 % keeps a margin while any exponent or digit slip in E, K, rho or C0 (>= 25 % in C0)
// fails. tungsten_alloy_jc derives K from C0 (see its sources), so for it the check is an identity.
TEST(MaterialPresets, BulkSoundSpeedAgreesWithHugoniotIntercept) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    if (word(p, "eos.type") != "mie_gruneisen") continue;
    const Elastic e = elastic(p);
    if (!std::isfinite(e.K)) continue;  // water: no elastic pair
    const double c_bulk = std::sqrt(e.K / num(p, "density"));
    const double c0 = num(p, "eos.sound_speed");
    EXPECT_NEAR(c_bulk / c0, 1.0, 0.10) << p.name << ": sqrt(K/rho) = " << c_bulk << " m/s, C0 = " << c0 << " m/s";
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

// E, nu, K, G describe one isotropic solid: the pair given must give 0 < nu < 1/2 and K, G > 0,
// and converting E, nu -> K, G -> E, nu must return the input (catches NaN or a typed E/nu swap).
// Where an independent shear modulus is recorded (Steinberg 1996 G0), G must agree within 10 %:
// Steinberg's G0 is a fitted reference value, and handbook moduli of one alloy vary by temper and
// test method by about 5 %; measured here: copper -3.6 %, 2024 -4.0 %, 6061 -6.2 %.
TEST(MaterialPresets, ElasticConstantsAreConsistent) {
  int cross = 0;
  for (const auto& p : library().presets()) {
    SCOPED_TRACE(p.name);
    const Elastic e = elastic(p);
    if (!std::isfinite(e.K)) continue;
    EXPECT_GT(e.K, 0.0);
    EXPECT_GT(e.G, 0.0);
    EXPECT_GT(e.nu, 0.0);
    EXPECT_LT(e.nu, 0.5);
    const double E2 = 9.0 * e.K * e.G / (3.0 * e.K + e.G);
    const double nu2 = (3.0 * e.K - 2.0 * e.G) / (2.0 * (3.0 * e.K + e.G));
    EXPECT_NEAR(E2 / e.E, 1.0, 1e-12);
    EXPECT_NEAR(nu2, e.nu, 1e-12);
    const auto g = p.cross_checks.find("steinberg_shear_modulus");
    if (g != p.cross_checks.end()) {
      EXPECT_NEAR(e.G / g->second, 1.0, 0.10) << "G = " << e.G << ", Steinberg G0 = " << g->second;
      ++cross;
    }
  }
  EXPECT_GE(cross, 3);
}

// Density against Steinberg's (1996) reference density of the same alloy: handbook densities of
// one alloy agree to well under 1 % (composition tolerance); a transposed digit (8690 for 8960)
// is 3 %. Measured: copper 0.34 %, 4340 0.26 %, 2024 0.54 %, 6061 0.11 %.
TEST(MaterialPresets, DensityAgreesWithSteinberg) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    const auto r = p.cross_checks.find("steinberg_density");
    if (r == p.cross_checks.end()) continue;
    EXPECT_NEAR(num(p, "density") / r->second, 1.0, 0.01) << p.name;
    ++checked;
  }
  EXPECT_GE(checked, 5);
}

// T* = (T - T0)/(Tm - T0) (Johnson & Cook 1983) needs Tm > T0, and a simulation starting at T0
// must start solid.
TEST(MaterialPresets, MeltTemperatureIsAboveReferenceAndInitial) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    if (!has(p, "melt_temperature")) continue;
    const double Tm = num(p, "melt_temperature"), T0 = num(p, "reference_temperature");
    EXPECT_GT(Tm, T0 + 300.0) << p.name;  // every metal here melts > 300 K above room temperature
    EXPECT_LT(num(p, "initial_temperature"), Tm) << p.name;
    EXPECT_GE(num(p, "initial_temperature"), T0) << p.name;
    ++checked;
  }
  EXPECT_GE(checked, 7);
}

// For a linear Us-up Hugoniot the pressure derivative of the bulk modulus at zero pressure is
// K' = 4s - 1, and the Dugdale-MacDonald relation Gamma = K'/2 - 1/2 (Phys. Rev. 89 (1953) 832)
// gives Gamma0 ~ 2s - 1. It is an estimate (measured here: copper 2 %, 4340 1 %, 6061 9 %,
// tungsten 13 %, 2024 19 %), so 25 % is allowed; it catches s and Gamma0 entered in each other's
// place (copper swapped: -51 %). Metals only: the relation does not hold for water.
TEST(MaterialPresets, GruneisenGammaIsConsistentWithHugoniotSlopeForMetals) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    if (word(p, "eos.type") != "mie_gruneisen" || p.model == "water") continue;
    const double s = num(p, "eos.hugoniot_slope"), gamma = num(p, "eos.gruneisen_gamma");
    EXPECT_NEAR(gamma / (2.0 * s - 1.0), 1.0, 0.25) << p.name << ": s = " << s << ", Gamma0 = " << gamma;
    ++checked;
  }
  EXPECT_GE(checked, 6);
}

// Johnson & Cook (1985): eps_f = [D1 + D2 exp(D3 sigma*)][1 + D4 ln(rate*)][1 + D5 T*], sigma* =
// sigma_mean/sigma_eq. Fracture strain falls with triaxiality (D3 < 0 for all three metals of that
// paper) and must be positive; at uniaxial tension (sigma* = 1/3) it is of order one for ductile
// metals (0.05 .. 5 rejects a misplaced decimal in D1 or D2).
TEST(MaterialPresets, JohnsonCookDamageConstantsArePlausible) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    if (word(p, "failure.criterion") != "johnson_cook_damage") continue;
    SCOPED_TRACE(p.name);
    const double d1 = num(p, "failure.d1"), d2 = num(p, "failure.d2"), d3 = num(p, "failure.d3");
    ASSERT_TRUE(std::isfinite(d1) && std::isfinite(d2) && std::isfinite(d3) && has(p, "failure.d4") &&
                has(p, "failure.d5"));
    EXPECT_LT(d3, 0.0);
    EXPECT_GT(d1 + d2, 0.0);  // sigma* = 0 (pure shear)
    const double eps_tension = d1 + d2 * std::exp(d3 / 3.0);
    EXPECT_GT(eps_tension, 0.05);
    EXPECT_LT(eps_tension, 5.0);
    EXPECT_GT(num(p, "failure.reference_strain_rate"), 0.0);
    ++checked;
  }
  EXPECT_GE(checked, 2);
}

// ---- geomodel (porous rock) presets ---------------------------------------------------------

namespace {

double cross(const MaterialPreset& p, const std::string& key) {
  const auto it = p.cross_checks.find(key);
  return it == p.cross_checks.end() ? NAN : it->second;
}

/// The limit function Ff(I1) of the geomodel (contract: Kayenta form a1 - a3 exp(a2 I1) - a4 I1
/// with a1 = STREN, a4 = YSLOPE and a2, a3 such that Ff(PEAKI1) = 0 and -dFf/dI1 = FSLOPE there;
/// Fossum & Brannon, SAND2009-2282). Tension positive, I1 = tr(sigma).
double limit_function(const MaterialPreset& p, double i1) {
  const double peak = num(p, "peak_i1"), f = num(p, "fslope");
  // Without stren the surface is the linear Drucker-Prager cone, the nonlinear form's limit as
  // STREN grows without bound (Fossum & Brannon, SAND2009-2282).
  if (!has(p, "stren")) return f * (peak - i1);
  const double stren = num(p, "stren");
  const double y = has(p, "yslope") ? num(p, "yslope") : 0.0;
  const double a2 = (f - y) / (stren - y * peak);
  const double a3 = (stren - y * peak) * std::exp(-a2 * peak);
  return stren - a3 * std::exp(a2 * i1) - y * i1;
}

/// The confidence of the source that covers a parameter key ("" if none does).
std::string confidence_of(const MaterialPreset& p, const std::string& key) {
  for (const auto& src : p.sources)
    for (const auto& k : src.keys)
      if (k == key) return src.confidence;
  return "";
}

/// Root of a continuous g on [lo, hi] with g(lo) < 0 < g(hi), by bisection (to 1e-12 relative).
template <class G>
double bisect(G g, double lo, double hi) {
  for (int i = 0; i < 200 && hi - lo > 1e-12 * std::max(std::abs(lo), std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

// The derived entries of the sandstone presets are recomputed from the data they were derived from
// (docs/material_data.md, "Berea-like sandstone"), and the set is checked against independent
// measurements of Berea. Tolerances:
// * P3 = -ln(1 - phi0): P3 is written with 4 significant digits (0.2357 for 0.23572), 1e-3.
// * P0 = -3 P*: exact by construction.
// * density = rho_grain (1 - phi0) (+ rho_water phi0 if saturated): rounded to 1 kg/m^3, 0.1 %.
// * unconfined compressive strength of the limit surface (root of sqrt(J2) = Ff(I1) on the path
//   I1 = -q, sqrt(J2) = q/sqrt(3)) against the 60 MPa it was fitted to: the fitted PEAKI1, STREN
//   and FSLOPE were rounded to two significant figures, which moves it to 62.2 MPa (+3.6 %); 10 %
//   allows for that while a wrong exponent or a sign slip in PEAKI1 fails.
// * K, G against Rice & Cleary's (1976) Berea (K 8.0 GPa, G 6.0 GPa; measured -17.5 %, -6.7 %):
//   different blocks of a natural rock, and Hart & Wang report their own set consistent to
//   +-20 %; 25 %.
// * P-wave speed sqrt((K + 4G/3)/rho) against the 2160-2290 m/s of the UMN (2007) Berea at low
//   stress (measured +16.5 % from the mean): static moduli at 10 MPa effective stress against
//   ultrasonic speeds of another block at low stress; 25 %.
TEST(MaterialPresets, GeomodelSandstoneDerivedValuesAndCrossChecks) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    // Porous presets only: a card with neither a crush curve nor a recorded porosity (the cement)
    // has no crush data to check; a preset with either one is checked in full.
    const bool porous = has(p, "crush_p3") || std::isfinite(cross(p, "porosity"));
    if (p.model != "geomodel" || !porous) continue;
    SCOPED_TRACE(p.name);
    const double phi = cross(p, "porosity");
    ASSERT_TRUE(std::isfinite(phi)) << "a geomodel preset records its porosity under cross_checks";
    EXPECT_NEAR(num(p, "crush_p3") / -std::log(1.0 - phi), 1.0, 1e-3);
    const bool saturated = has(p, "fluid_bulk_modulus") && num(p, "fluid_bulk_modulus") > 0.0;
    const double rho = cross(p, "grain_density") * (1.0 - phi) +
                       (saturated ? cross(p, "water_density") * phi : 0.0);
    // A density a seed document states (the thesis's 2300 kg/m^3) is taken as stated, not derived
    // from the skeleton's porosity.
    if (confidence_of(p, "density") != "seed") {
      EXPECT_NEAR(num(p, "density") / rho, 1.0, 1e-3);
    }
    EXPECT_GT(num(p, "peak_i1"), 0.0);   // tensile vertex: tension positive
    EXPECT_LT(num(p, "crush_p0"), 0.0);  // cap in compression
    EXPECT_GT(num(p, "crush_p1"), 0.0);

    // Uniaxial compression point on the limit surface, and the cap must start beyond it (the cap
    // would otherwise cut the unconfined strength the limit surface was fitted to).
    const double ucs =
        bisect([&](double q) { return q / std::sqrt(3.0) - limit_function(p, -q); }, 0.0, 1e10);
    const double x = num(p, "crush_p0"), cr = num(p, "cap_ratio");
    const double kappa =
        bisect([&](double k) { return k - x - cr * limit_function(p, k); }, x, num(p, "peak_i1"));
    EXPECT_LT(kappa, -ucs) << "cap starts at I1 = " << kappa;
    EXPECT_GT(kappa, x);

    if (const double ucs_ref = cross(p, "unconfined_compressive_strength");
        std::isfinite(ucs_ref)) {
      EXPECT_NEAR(ucs / ucs_ref, 1.0, 0.10) << "UCS of the limit surface " << ucs;
    }
    if (const double pstar = cross(p, "critical_pressure"); std::isfinite(pstar)) {
      EXPECT_DOUBLE_EQ(num(p, "crush_p0"), -3.0 * pstar);
    }
    const double K = num(p, "bulk_modulus"), G = num(p, "shear_modulus");
    if (const double k_rc = cross(p, "rice_cleary_bulk_modulus"); std::isfinite(k_rc)) {
      EXPECT_NEAR(K / k_rc, 1.0, 0.25);
      EXPECT_NEAR(G / cross(p, "rice_cleary_shear_modulus"), 1.0, 0.25);
    }
    if (const double lo = cross(p, "p_wave_speed_low"); std::isfinite(lo)) {
      const double cp = std::sqrt((K + 4.0 * G / 3.0) / num(p, "density"));
      EXPECT_NEAR(cp / (0.5 * (lo + cross(p, "p_wave_speed_high"))), 1.0, 0.25) << "c_p = " << cp;
    }
    ++checked;
  }
  EXPECT_GE(checked, 4);  // the four sandstones
}

// The class-G-like cement (a geomodel card without porosity) against the data its values were
// derived from (cross_checks). Tolerances:
// * density = (1 + w/c) / (1/rho_c + (w/c)/rho_w): rounded to 1 kg/m^3, 0.1 %.
// * unconfined compressive strength of the limit surface against the 40 MPa FSLOPE was fitted to,
//   and its high-pressure limit sqrt(J2) -> STREN against S_max f'c / sqrt(3) (Holmquist, Johnson &
//   Cook 1993, S_max = 7): FSLOPE and STREN are written with 4 significant figures (0.4935 for
//   0.49346, 161.7 for 161.66 MPa), which moves each by < 0.04 %; 0.1 %.
// * tensile vertex PEAKI1 = 3 T exactly; E and nu from K and G against the recorded 13 GPa and
//   0.20, 0.5 % (K and G are written to 2 significant figures: E = 12.96 GPa).
// * the shear strength must saturate: sqrt(J2) at 10 GPa of pressure within 1 % of STREN. The
//   linear cone the demo's cement had (FSLOPE 0.457 through the same vertex) gives 13.7 GPa there,
//   85x as much; that unbounded strength is what this card replaces (docs/material_data.md).
TEST(MaterialPresets, CementPresetMeetsItsStrengthsAndSaturates) {
  const MaterialPreset& p = library().get("cement_class_g");
  ASSERT_EQ(p.model, "geomodel");
  EXPECT_FALSE(has(p, "crush_p3")) << "no porosity: the pores hold the mix water (notes)";
  const double wc = cross(p, "water_cement_ratio");
  const double slurry = (1.0 + wc) / (1.0 / cross(p, "cement_grain_density") + wc / 1000.0);
  EXPECT_NEAR(num(p, "density") / slurry, 1.0, 1e-3);
  const double ucs_ref = cross(p, "unconfined_compressive_strength");
  const double ucs =
      bisect([&](double q) { return q / std::sqrt(3.0) - limit_function(p, -q); }, 0.0, 1e10);
  EXPECT_NEAR(ucs / ucs_ref, 1.0, 1e-3) << "UCS of the limit surface " << ucs;
  EXPECT_DOUBLE_EQ(num(p, "peak_i1"), 3.0 * cross(p, "tensile_strength"));
  const double smax = cross(p, "hjc_max_normalised_strength");
  EXPECT_NEAR(num(p, "stren") / (smax * ucs_ref / std::sqrt(3.0)), 1.0, 1e-3);
  EXPECT_NEAR(limit_function(p, -3.0 * 10e9) / num(p, "stren"), 1.0, 1e-2);
  const Elastic e = elastic(p);
  EXPECT_NEAR(e.E / cross(p, "youngs_modulus"), 1.0, 5e-3);
  EXPECT_NEAR(e.nu / cross(p, "poisson_ratio"), 1.0, 5e-3);
}

// The saturated sandstone is the drained skeleton plus water: every key of the drained preset
// except the density is repeated unchanged. Its Biot-Gassmann undrained bulk modulus
// K_u = K + (1 - K/Ks)^2 / (phi/Kf + (1 - phi)/Ks - K/Ks^2) (Gassmann 1951; geomodel contract)
// must exceed the drained K and is compared with Hart & Wang's (1995) measured 15.8 GPa: 12.5 GPa,
// -21 %; they state their Berea moduli are mutually consistent only to +-20 %, hence 25 %. The
// grain modulus (36 GPa) is compared with quartz (37 GPa), 10 %: Berea is ~80 % quartz with
// feldspar and clay (softer), so a few % below quartz is expected; a GPa/MPa slip fails.
TEST(MaterialPresets, SaturatedSandstoneIsTheDrainedSkeletonPlusWater) {
  const MaterialPreset& dry = library().get("sandstone_berea_drained");
  const MaterialPreset& wet = library().get("sandstone_berea_saturated");
  for (const auto& [k, v] : flatten_parameters(dry.parameters)) {
    if (k == "density") continue;
    EXPECT_EQ(num(wet, k), num(dry, k)) << k;
  }
  EXPECT_GT(num(wet, "density"), num(dry, "density"));
  EXPECT_FALSE(has(dry, "fluid_bulk_modulus"));
  const double K = num(wet, "bulk_modulus"), Ks = num(wet, "matrix_bulk_modulus");
  const double Kf = num(wet, "fluid_bulk_modulus"), phi = cross(wet, "porosity");
  const double Ku = K + std::pow(1.0 - K / Ks, 2) / (phi / Kf + (1.0 - phi) / Ks - K / (Ks * Ks));
  EXPECT_GT(Ku, K);
  EXPECT_NEAR(Ku / cross(wet, "hart_wang_undrained_bulk_modulus"), 1.0, 0.25) << "K_u = " << Ku;
  EXPECT_NEAR(Ks / cross(wet, "quartz_bulk_modulus"), 1.0, 0.10);
}

// The thesis's sandstone (seed 000) is the drained Berea skeleton with the two things the thesis
// states: its density, 2300 kg/m^3, and a linear limit surface (no stren: shear strength grows
// with pressure without bound). The density is checked against the thesis's own Table 5.3 row 3,
// whose hydrodynamic depth L sqrt(rho_p / rho_t) it prints as 21.27 cm for the 73.54 mm rod of
// 19235 kg/m^3; the printed figure has four digits, so it must agree to 5e-4 relative.
TEST(MaterialPresets, ThesisSandstoneIsBereaWithTheThesisDensityAndALinearSurface) {
  const MaterialPreset& berea = library().get("sandstone_berea_drained");
  const MaterialPreset& thesis = library().get("sandstone_thesis_drained");
  for (const auto& [k, v] : flatten_parameters(thesis.parameters)) {
    if (k == "density") continue;
    EXPECT_EQ(num(thesis, k), num(berea, k)) << k;
  }
  EXPECT_FALSE(has(thesis, "stren"));
  EXPECT_FALSE(has(thesis, "yslope"));
  EXPECT_TRUE(has(berea, "stren"));
  const double depth = 73.54e-3 * std::sqrt(19235.0 / num(thesis, "density"));
  EXPECT_NEAR(depth / cross(thesis, "thesis_hydrodynamic_depth_row3"), 1.0, 5e-4) << depth;
}

// The thesis's undrained sandstone is its drained one plus the pore fluid of the saturated Berea
// preset, at the thesis's one density (2300 kg/m^3): every drained key is repeated unchanged, the
// fluid keys are the saturated Berea's, and it has no stren either.
TEST(MaterialPresets, ThesisSaturatedSandstoneIsTheThesisSkeletonPlusBereaWater) {
  const MaterialPreset& dry = library().get("sandstone_thesis_drained");
  const MaterialPreset& wet = library().get("sandstone_thesis_saturated");
  const MaterialPreset& berea_wet = library().get("sandstone_berea_saturated");
  for (const auto& [k, v] : flatten_parameters(dry.parameters)) EXPECT_EQ(num(wet, k), num(dry, k)) << k;
  for (const char* k : {"fluid_bulk_modulus", "initial_pore_pressure", "matrix_bulk_modulus"})
    EXPECT_EQ(num(wet, k), num(berea_wet, k)) << k;
  EXPECT_FALSE(has(wet, "stren"));
}

// The sandstone presets in the real geomodel (once registered), on a hydrostatic compression path
// of 2000 equal log-strain steps: pores start to collapse when the EFFECTIVE pressure -I1/3 - pf
// reaches P* = 380 MPa (the cross-checked critical pressure), drained or saturated; past P* the
// drained porosity follows the crush curve, phi = 1 - exp(-P3 exp(P1 (X - P0))) with X = I1 at the
// cap tip (thesis seed 000 eq. 4.5), and at 500 MPa it is the 0.179 of docs/material_data.md.
// Tolerances: one step raises the pressure by K dev = 6.6 GPa x 6.5e-5 = 0.43 MPa drained (about
// twice that saturated, undrained K 12.5 GPa), so the first plastic step lies within 2 MPa above
// P*; the porosity identity holds to rounding (1e-9); the 500 MPa value is read one step past
// 500 MPa (<= 0.5 MPa, porosity change ~1e-4) and compared with the 3-digit documented value (2e-3).
TEST(MaterialPresets, SandstonePresetsCrushAtTheirCriticalPressureInTheRealModel) {
  ASSERT_NE(find_material("geomodel"), nullptr) << "the geomodel must be registered";
  const double pstar = cross(library().get("sandstone_berea_drained"), "critical_pressure");
  for (const char* name : {"sandstone_berea_drained", "sandstone_berea_saturated", "sandstone_thesis_drained",
                           "sandstone_thesis_saturated"}) {
    SCOPED_TRACE(name);
    const MaterialPreset& p = library().get(name);
    const ParamValues v = preset_param_values(p, find_material("geomodel")->params);
    test::PointDriver d("geomodel", v);
    const bool saturated = v.number_or("fluid_bulk_modulus", 0.0) > 0.0;
    const int steps = 2000;
    const double ev_end = -0.13;
    double p_eff_prev = 0.0, p_eff_yield = NAN, phi_500 = NAN;
    for (int s = 1; s <= steps; ++s) {
      d.advance(std::exp(ev_end * s / steps / 3.0) * Mat3::identity(), 1e-3);
      const double i1 = trace(d.stress_bar());
      const double pf = saturated ? d.state("pore_pressure") : 0.0;
      const double p_eff = -i1 / 3.0 - pf;
      if (std::isnan(p_eff_yield) && d.state("plastic_volumetric_strain") < 0.0) {
        p_eff_yield = p_eff;
        EXPECT_LT(p_eff_prev, pstar) << "elastic up to the step before";
      }
      p_eff_prev = p_eff;
      if (!saturated && d.state("plastic_volumetric_strain") < 0.0) {
        const double phi =
            1.0 - std::exp(-num(p, "crush_p3") * std::exp(num(p, "crush_p1") * (i1 - num(p, "crush_p0"))));
        EXPECT_NEAR(d.state("porosity"), phi, 1e-9) << "step " << s;
        if (std::isnan(phi_500) && p_eff >= 500e6) phi_500 = d.state("porosity");
      }
    }
    ASSERT_TRUE(std::isfinite(p_eff_yield)) << "no pore collapse on the path";
    EXPECT_GE(p_eff_yield, pstar - 1e-6 * pstar);
    EXPECT_LE(p_eff_yield, pstar + 2e6);
    if (!saturated) {
      ASSERT_TRUE(std::isfinite(phi_500));
      EXPECT_NEAR(phi_500, 0.179, 2e-3);
    }
  }
}

// Presets of registered models are read exactly as a deck would read them (flattened names,
// ranges, choices, defaults) and construct through the registry. The Taylor-anvil copper must
// equal the model's own CATALOGUE B6 example (J2Plasticity::example_params), bit for bit.
// Explosives (issue 15 item 1): every JWL set is self-consistent at its CJ state. The CJ
// isentrope through (X_CJ, P_CJ) must be tangent to the Rayleigh line (slope -rho0 D^2) and give
// the cited detonation energy E0 through the Hugoniot energy equation. Published sets are fits
// that satisfy both to a few tenths of a percent (measured: TNT 0.03 % / 0.13 %, Comp B and LX-14
// < 0.05 %), so 0.5 % catches a mistyped digit in any of A, B, R1, R2, omega, D or P_CJ.
TEST(MaterialPresets, ExplosiveJwlSetsAreConsistentAtTheCjState) {
  int checked = 0;
  for (const auto& p : library().presets()) {
    if (p.model != "explosive") continue;
    SCOPED_TRACE(p.name);
    ProductsEos e;
    e.rho0 = num(p, "density");
    e.D = num(p, "detonation_speed");
    e.p_cj = num(p, "cj_pressure");
    e.A = num(p, "jwl.a");
    e.B = num(p, "jwl.b");
    e.R1 = num(p, "jwl.r1");
    e.R2 = num(p, "jwl.r2");
    e.omega = num(p, "jwl.omega");
    const double X = cj_volume(e);
    const double slope = products_isentropic_slope(e, X, cj_isentrope_energy(e, X));
    EXPECT_NEAR(slope / (-e.rho0 * e.D * e.D), 1.0, 0.005);
    EXPECT_NEAR(detonation_energy(e) / num(p, "detonation_energy"), 1.0, 0.005);
    ++checked;
  }
  EXPECT_GE(checked, 3);  // TNT, Composition B, the PBXN-9 stand-in
}

TEST(MaterialPresets, RegisteredModelsConstructFromPresets) {
  int built = 0;
  for (const auto& p : library().presets()) {
    const MaterialFactory* f = find_material(p.model);
    if (!f) continue;
    SCOPED_TRACE(p.name);
    const ParamValues v = preset_param_values(p, f->params);
    const auto m = f->create(p.name, v);
    ASSERT_NE(m, nullptr);
    EXPECT_EQ(std::string(m->model()), p.model);
    EXPECT_EQ(m->density(), num(p, "density"));
    ++built;
  }
  EXPECT_GE(built, 1);

  const MaterialPreset& b6 = library().get("copper_taylor_b6_j2");
  const MaterialFactory* j2 = find_material(b6.model);
  ASSERT_NE(j2, nullptr);
  ASSERT_NE(j2->example, nullptr);
  const ParamValues example = j2->example();
  const ParamValues v = preset_param_values(b6, j2->params);
  for (const auto& [k, x] : example) EXPECT_EQ(v.at(k), x) << k;
  for (const auto& [k, x] : flatten_parameters(b6.parameters)) EXPECT_TRUE(example.count(k)) << k;
}

TEST(MaterialPresets, ParamValuesRejectUnknownOutOfRangeAndMissingKeys) {
  const MaterialFactory* j2 = find_material("j2_plasticity");
  ASSERT_NE(j2, nullptr);
  auto lib = MaterialPresetLibrary::parse(R"(schema_version: 1
presets:
  typo:
    model: j2_plasticity
    parameters:
      density: 8930
      youngs_modulus: 117e9
      poisson_ratio: 0.35
      yield_strees: 4e8
    sources:
      - {keys: [density, youngs_modulus, poisson_ratio, yield_strees], cite: "a test of the checks", confidence: seed}
  negative:
    model: j2_plasticity
    parameters: {density: -1, youngs_modulus: 117e9, poisson_ratio: 0.35, yield_stress: 4e8}
    sources:
      - {keys: [density, youngs_modulus, poisson_ratio, yield_stress], cite: "a test of the checks", confidence: seed}
)",
                                          "t.yaml");
  try {
    (void)preset_param_values(lib.get("typo"), j2->params);
    FAIL() << "expected an error";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.line(), 9);
    EXPECT_EQ(e.key_path(), "presets.typo.yield_strees");
    EXPECT_NE(std::string(e.what()).find("did you mean 'yield_stress'"), std::string::npos) << e.what();
  }
  // A required parameter the preset lacks is reported at the preset's name (line 12 here).
  MaterialPreset no_yield = lib.get("negative");
  // reset(), not operator=: a yaml-cpp assignment would overwrite the node shared with `lib`.
  no_yield.parameters.reset(YAML::Load("{density: 8930, youngs_modulus: 117e9, poisson_ratio: 0.35}"));
  try {
    (void)preset_param_values(no_yield, j2->params);
    FAIL() << "expected an error";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.line(), 12);
    EXPECT_EQ(e.key_path(), "presets.negative.yield_stress");
    EXPECT_NE(std::string(e.what()).find("missing required parameter"), std::string::npos) << e.what();
  }
  try {
    (void)preset_param_values(lib.get("negative"), j2->params);
    FAIL() << "expected an error";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "presets.negative.density");
    EXPECT_NE(std::string(e.what()).find("> 0"), std::string::npos) << e.what();
  }
}

// ---- file location ---------------------------------------------------------------------------

TEST(MaterialPresets, DefaultPathIsTheSourceTreeUnlessTheEnvironmentOverrides) {
  const char* old = std::getenv(kMaterialPresetsEnv);
  const std::string saved = old ? old : "";
  ::unsetenv(kMaterialPresetsEnv);
  EXPECT_TRUE(std::filesystem::equivalent(default_material_presets_path(), presets_path()));
  EXPECT_EQ(MaterialPresetLibrary::load_default().names(), library().names());

  test::TempDir dir;
  const auto file = dir.path / "mine.yaml";
  std::ofstream(file) << "schema_version: 1\npresets:\n  only:\n    model: linear_elastic\n"
                         "    parameters: {density: 1000, bulk_modulus: 2e9, shear_modulus: 1e9}\n"
                         "    sources: [{keys: [density, bulk_modulus, shear_modulus], cite: \"my own lab data\","
                         " confidence: seed}]\n";
  ::setenv(kMaterialPresetsEnv, file.c_str(), 1);
  EXPECT_EQ(default_material_presets_path(), file.string());
  EXPECT_EQ(MaterialPresetLibrary::load_default().names(), std::vector<std::string>{"only"});
  if (old)
    ::setenv(kMaterialPresetsEnv, saved.c_str(), 1);
  else
    ::unsetenv(kMaterialPresetsEnv);

  try {
    (void)MaterialPresetLibrary::load((dir.path / "missing.yaml").string());
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(kMaterialPresetsEnv), std::string::npos) << e.what();
  }
}

// ---- malformed files: each error names the file, the line and the key path ---------------------

namespace {

/// A one-preset file with `body` as the preset's map (indented by 4).
std::string one_preset(const std::string& body) {
  return "schema_version: 1\npresets:\n  cu:\n" + body;
}

const std::string kGood = R"(    model: linear_elastic
    parameters:
      density: 8930
      youngs_modulus: 117e9
      poisson_ratio: 0.35
    sources:
      - keys: [density, youngs_modulus, poisson_ratio]
        cite: OTM report SAND2020-9716 ch. 4
        confidence: seed
)";

struct Expect {
  int line;
  std::string key_path;
  std::string message_part;
};

void expect_error(const std::string& text, const Expect& want) {
  try {
    (void)MaterialPresetLibrary::parse(text, "presets.yaml");
    ADD_FAILURE() << "expected an error for:\n" << text;
  } catch (const DeckError& e) {
    EXPECT_EQ(e.file(), "presets.yaml");
    EXPECT_EQ(e.line(), want.line) << e.what();
    EXPECT_EQ(e.key_path(), want.key_path) << e.what();
    EXPECT_NE(std::string(e.what()).find(want.message_part), std::string::npos) << e.what();
  }
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return s.replace(pos, from.size(), to);
}

}  // namespace

TEST(MaterialPresetsFile, GoodMinimalFileParses) {
  const auto lib = MaterialPresetLibrary::parse(one_preset(kGood), "presets.yaml");
  ASSERT_EQ(lib.names(), std::vector<std::string>{"cu"});
  EXPECT_EQ(lib.get("cu").line, 3);
  EXPECT_EQ(lib.get("cu").sources.at(0).confidence, "seed");
}

TEST(MaterialPresetsFile, SyntaxErrorNamesFileAndLine) {
  // An unclosed flow list on line 8; yaml-cpp notices it at the next key (line 9, 1-based).
  try {
    (void)MaterialPresetLibrary::parse(one_preset(replace(kGood, "poisson_ratio: 0.35\n", "poisson_ratio: [0.35\n")),
                                       "presets.yaml");
    FAIL() << "expected an error";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.file(), "presets.yaml");
    EXPECT_GE(e.line(), 8) << e.what();
    EXPECT_LE(e.line(), 9) << e.what();
    EXPECT_NE(std::string(e.what()).find("YAML syntax error"), std::string::npos) << e.what();
  }
}

TEST(MaterialPresetsFile, MissingModel) {
  expect_error(one_preset(replace(kGood, "    model: linear_elastic\n", "")),
               {3, "presets.cu.model", "missing 'model'"});
}

TEST(MaterialPresetsFile, UnknownPresetKeySuggestsTheRightOne) {
  expect_error(one_preset(replace(kGood, "    sources:", "    source:")),
               {9, "presets.cu.source", "did you mean 'sources'"});
}

TEST(MaterialPresetsFile, ParameterWithoutSource) {
  expect_error(
      one_preset(replace(kGood, "keys: [density, youngs_modulus, poisson_ratio]", "keys: [density, youngs_modulus]")),
      {8, "presets.cu.parameters.poisson_ratio", "has no source"});
}

TEST(MaterialPresetsFile, ParameterUnderTwoSources) {
  expect_error(
      one_preset(kGood + "      - keys: [density]\n        cite: another handbook\n        confidence: recalled\n"),
      {6, "presets.cu.parameters.density", "listed under 2 sources"});
}

TEST(MaterialPresetsFile, SourceKeyThatNamesNoParameter) {
  expect_error(one_preset(replace(kGood, "keys: [density, youngs_modulus, poisson_ratio]",
                                  "keys: [density, youngs_modulus, poisson_ratio, poison_ratio]")),
               {10, "presets.cu.sources.0.keys.3", "did you mean 'poisson_ratio'"});
}

TEST(MaterialPresetsFile, UnknownConfidenceAndCheckedWithoutVia) {
  expect_error(one_preset(replace(kGood, "confidence: seed", "confidence: seeded")),
               {12, "presets.cu.sources.0.confidence", "did you mean 'seed'"});
  expect_error(one_preset(replace(kGood, "confidence: seed", "confidence: checked")),
               {10, "presets.cu.sources.0.via", "needs 'via'"});
}

TEST(MaterialPresetsFile, GroupsAreOneLevelMapsOfScalars) {
  const std::string with_eos =
      replace(kGood, "      poisson_ratio: 0.35\n", "      poisson_ratio: 0.35\n      eos:\n        type: {deep: 1}\n");
  expect_error(one_preset(with_eos), {10, "presets.cu.parameters.eos.type", "expected a number or a word"});
  // A group covered by "eos.*" is accepted.
  const std::string ok =
      replace(replace(kGood, "      poisson_ratio: 0.35\n", "      poisson_ratio: 0.35\n      eos: {type: linear}\n"),
              "poisson_ratio]", "poisson_ratio, eos.*]");
  const auto lib = MaterialPresetLibrary::parse(one_preset(ok), "presets.yaml");
  EXPECT_EQ(flatten_parameters(lib.get("cu").parameters).back().first, "eos.type");
}

TEST(MaterialPresetsFile, DuplicatePresetAndWrongSchema) {
  expect_error(one_preset(kGood) + "  cu:\n" + kGood, {13, "presets.cu", "duplicate"});
  expect_error(replace(one_preset(kGood), "schema_version: 1", "schema_version: 2"),
               {1, "schema_version", "expected schema_version: 1"});
  expect_error("schema_version: 1\npresets: {}\n", {2, "presets", "expected a map of named presets"});
}

// ---- merging a preset into a deck material -------------------------------------------------

TEST(MaterialPresetMerge, DeckKeysWinAndGroupsMergeKeyByKey) {
  const MaterialPreset& cu = library().get("copper_ofhc_jc");
  const YAML::Node deck = YAML::Load(R"(preset: copper_ofhc_jc
jc_a: 1.0e8
eos: {min_pressure: -1.0e9}
failure: {erosion: zero_stress, d1: 0.6}
)");
  const YAML::Node m = merge_preset_into(cu, deck);
  EXPECT_EQ(m["model"].as<std::string>(), "johnson_cook");
  EXPECT_FALSE(m["preset"].IsDefined());
  EXPECT_EQ(m["jc_a"].as<double>(), 1.0e8);                  // deck
  EXPECT_EQ(m["jc_b"].as<double>(), 292.0e6);                // preset
  EXPECT_EQ(m["eos"]["min_pressure"].as<double>(), -1.0e9);  // deck, added to the group
  EXPECT_EQ(m["eos"]["sound_speed"].as<double>(), 3940.0);   // preset, kept in the group
  EXPECT_EQ(m["failure"]["d1"].as<double>(), 0.6);           // deck replaces one group key
  EXPECT_EQ(m["failure"]["d2"].as<double>(), 4.89);          // preset
  EXPECT_EQ(m["failure"]["erosion"].as<std::string>(), "zero_stress");
  // The deck's own nodes keep their positions (for error messages at the deck's lines).
  EXPECT_EQ(m["jc_a"].Mark().line, 1);
  // The preset itself is untouched by changes to the result.
  YAML::Node out = m;
  out["jc_b"] = 1.0;
  out["eos"]["sound_speed"] = 1.0;
  EXPECT_EQ(num(cu, "jc_b"), 292.0e6);
  EXPECT_EQ(num(cu, "eos.sound_speed"), 3940.0);
}

TEST(MaterialPresetMerge, ElasticPairIsReplacedAsAWhole) {
  const MaterialPreset& cu = library().get("copper_ofhc_jc");  // gives bulk and shear moduli
  const YAML::Node m = merge_preset_into(cu, YAML::Load("{youngs_modulus: 1.2e11, poisson_ratio: 0.34}"));
  EXPECT_FALSE(m["bulk_modulus"].IsDefined());
  EXPECT_FALSE(m["shear_modulus"].IsDefined());
  EXPECT_EQ(m["youngs_modulus"].as<double>(), 1.2e11);
  EXPECT_EQ(m["density"].as<double>(), 8960.0);
}

TEST(MaterialPresetMerge, ModelMismatchAndNonMapGroupAreErrors) {
  const MaterialPreset& cu = library().get("copper_ofhc_jc");
  EXPECT_THROW((void)merge_preset_into(cu, YAML::Load("{model: j2_plasticity}")), Error);
  EXPECT_NO_THROW((void)merge_preset_into(cu, YAML::Load("{model: johnson_cook}")));
  EXPECT_THROW((void)merge_preset_into(cu, YAML::Load("{eos: mie_gruneisen}")), Error);
  EXPECT_NO_THROW((void)merge_preset_into(cu, YAML::Node()));  // no deck keys: the preset as it is
}

// The path the deck reader will take: merge, then read the merged parameters for the model.
TEST(MaterialPresetMerge, MergedTaylorCopperConstructsWithTheDeckOverride) {
  const MaterialPreset& b6 = library().get("copper_taylor_b6_j2");
  const YAML::Node merged = merge_preset_into(b6, YAML::Load("{preset: copper_taylor_b6_j2, yield_stress: 3.0e8}"));
  MaterialPreset as_read = b6;
  as_read.parameters.reset(YAML::Node(YAML::NodeType::Map));  // rebind, do not overwrite the library's node
  for (auto it = merged.begin(); it != merged.end(); ++it)
    if (it->first.as<std::string>() != "model") as_read.parameters[it->first] = it->second;
  const MaterialFactory* j2 = find_material("j2_plasticity");
  ASSERT_NE(j2, nullptr);
  const ParamValues v = preset_param_values(as_read, j2->params);
  EXPECT_EQ(v.at("yield_stress"), 3.0e8);
  EXPECT_EQ(v.at("hardening_modulus"), 100.0e6);
  EXPECT_NE(j2->create("b6", v), nullptr);
  EXPECT_EQ(num(library().get("copper_taylor_b6_j2"), "yield_stress"), 400.0e6);  // the library is untouched
}

}  // namespace test_material_presets
