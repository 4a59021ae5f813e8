#include "materials/failure.hpp"

#include <string>

#include <fmt/format.h>

namespace ballista {

namespace {

// Function-local statics: failure_param_specs() runs during the static initialisation of the
// model files (registration), when namespace-scope objects of this file may not exist yet.
// The names in the order of the enumerators (FailureCriterion, ErosionRule in failure.hpp), so a
// name's position is its value.
const std::vector<std::string>& criteria() {
  static const std::vector<std::string> v = {"none", "johnson_cook_damage", "melt", "tepla", "drucker_stability",
                                             "max_stress"};
  return v;
}
const std::vector<std::string>& erosion_rules() {
  static const std::vector<std::string> v = {"none", "allow_no_tension", "allow_no_shear", "zero_stress"};
  return v;
}
static_assert(static_cast<int>(FailureCriterion::MaxStress) == 5 && static_cast<int>(ErosionRule::ZeroStress) == 3,
              "a new enumerator needs its name at its position in the lists above");

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

/// The enumerator named `w` in `names` (listed in the enumerators' order), or a ParamError at `key`.
template <class Enum>
Enum enum_from(const std::vector<std::string>& names, const std::string& w, const std::string& key) {
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == w) return static_cast<Enum>(i);
  throw ParamError(key, "unknown " + key + " '" + w + "' (expected one of: " + joined(names) + ")");
}

FailureCriterion criterion_from(const std::string& w) {
  return enum_from<FailureCriterion>(criteria(), w, "failure.criterion");
}

ErosionRule erosion_from(const std::string& w) {
  return enum_from<ErosionRule>(erosion_rules(), w, "failure.erosion");
}

/// The number `key`, which `criterion` requires.
double required(const ParamValues& v, const char* key, const std::string& criterion) {
  if (!v.given(key))
    throw ParamError(key, std::string(key) + " is required when failure.criterion is " + criterion);
  return v.at(key);
}

void check_positive(const char* key, double x) {
  if (!(x > 0.0)) throw ParamError(key, std::string(key) + " must be > 0");
}

}  // namespace

std::vector<ParamSpec> failure_param_specs() {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ParamSpec criterion{"failure.criterion", "",
                      "failure criterion (thesis eq. 6.5-6.10); a failed point is eroded by failure.erosion", false};
  criterion.choices = criteria();
  criterion.default_choice = "none";
  ParamSpec erosion{"failure.erosion", "",
                    "stress of a failed point (eq. 6.11-6.14); none still evolves damage but keeps the stress", false};
  erosion.choices = erosion_rules();
  erosion.default_choice = "none";
  auto jc = [&](const char* name, const char* what) {
    return ParamSpec{name, "1", std::string("johnson_cook_damage: ") + what + " (required with it)", false, nan};
  };
  return {
      criterion,
      erosion,
      jc("failure.d1", "D1 of eps_f = [D1 + D2 exp(D3 sigma*)][1 + D4 ln edot*][1 + D5 T*]"),
      jc("failure.d2", "D2"),
      jc("failure.d3", "D3 (multiplies the triaxiality sigma* = tr(sigma)/(3 sigma_eq))"),
      jc("failure.d4", "D4 (rate factor; edot* = edot_p/edot_0, taken as 1 below 1)"),
      jc("failure.d5", "D5 (temperature factor; non-zero needs a model that tracks T)"),
      {"failure.reference_strain_rate", "1/s", "johnson_cook_damage: reference plastic strain rate edot_0", false, 1.0,
       0.0, inf, true, false},
      {"failure.initial_porosity", "1",
       "tepla: initial porosity f_0 (f stays f_0 plus nucleation: J2 flow is isochoric)", false, 0.0, 0.0, 1.0,
       false, true},
      {"failure.critical_porosity", "1", "tepla: critical porosity f_c (required with tepla)", false, nan, 0.0, 1.0,
       true, false},
      {"failure.fracture_strain", "1", "tepla: equivalent plastic strain at fracture eps_p^f (required with tepla)",
       false, nan, 0.0, inf, true, false},
      {"failure.nucleation_porosity", "1", "tepla: porosity f_N nucleated by strain (Chu-Needleman; 0 = none)", false,
       0.0, 0.0, 1.0, false, true},
      {"failure.nucleation_strain", "1", "tepla: mean plastic strain eps_N of nucleation", false, 0.3, 0.0, inf, false,
       false},
      {"failure.nucleation_stddev", "1", "tepla: standard deviation s_N of nucleation", false, 0.1, 0.0, inf, true,
       false},
      {"failure.max_stress", "Pa", "max_stress: von Mises stress sigma_max at failure (required with it)", false, nan,
       0.0, inf, true, false},
  };
}

FailureModel make_failure(const ParamValues& v, ModelCapabilities caps) {
  FailureModel m;
  const std::string crit = v.choice("failure.criterion", "none");
  m.criterion = criterion_from(crit);
  m.erosion = erosion_from(v.choice("failure.erosion", "none"));
  if (m.criterion == FailureCriterion::None) {
    if (m.erosion != ErosionRule::None)
      throw ParamError("failure.erosion",
                       "failure.erosion has no effect without a failure.criterion (expected one of: " +
                           joined(criteria()) + ")");
    return m;
  }
  // What the model must track (declared by its kernel, see ModelCapabilities).
  const bool needs_eqps = m.criterion == FailureCriterion::JohnsonCookDamage ||
                          m.criterion == FailureCriterion::Tepla ||
                          m.criterion == FailureCriterion::DruckerStability;
  if (needs_eqps && !caps.plastic_strain)
    throw ParamError("failure.criterion", "failure.criterion " + crit +
                                              " needs the equivalent plastic strain, which this model does not track "
                                              "(use a plasticity model)");
  if (m.criterion == FailureCriterion::Melt && !caps.temperature)
    throw ParamError("failure.criterion",
                     "failure.criterion melt needs the temperature, which this model does not track (use a model with "
                     "a melt temperature, e.g. johnson_cook)");
  switch (m.criterion) {
    case FailureCriterion::JohnsonCookDamage:
      m.d1 = required(v, "failure.d1", crit);
      m.d2 = required(v, "failure.d2", crit);
      m.d3 = required(v, "failure.d3", crit);
      m.d4 = required(v, "failure.d4", crit);
      m.d5 = required(v, "failure.d5", crit);
      m.reference_rate = v.number_or("failure.reference_strain_rate", 1.0);
      check_positive("failure.reference_strain_rate", m.reference_rate);
      if (m.d5 != 0.0 && !caps.temperature)
        throw ParamError("failure.d5", "failure.d5 must be 0 for a model that does not track the temperature");
      break;
    case FailureCriterion::Tepla:
      m.critical_porosity = required(v, "failure.critical_porosity", crit);
      m.fracture_strain = required(v, "failure.fracture_strain", crit);
      m.initial_porosity = v.number_or("failure.initial_porosity", 0.0);
      m.nucleation_porosity = v.number_or("failure.nucleation_porosity", 0.0);
      m.nucleation_strain = v.number_or("failure.nucleation_strain", 0.3);
      m.nucleation_stddev = v.number_or("failure.nucleation_stddev", 0.1);
      check_positive("failure.critical_porosity", m.critical_porosity);
      check_positive("failure.fracture_strain", m.fracture_strain);
      check_positive("failure.nucleation_stddev", m.nucleation_stddev);
      if (!(m.initial_porosity >= 0.0 && m.initial_porosity < m.critical_porosity))
        throw ParamError("failure.initial_porosity",
                         "failure.initial_porosity must be >= 0 and below failure.critical_porosity (" +
                             fmt::format("{:.6g}", m.critical_porosity) + ")");
      if (!(m.nucleation_porosity >= 0.0))
        throw ParamError("failure.nucleation_porosity", "failure.nucleation_porosity must be >= 0");
      break;
    case FailureCriterion::MaxStress:
      m.max_stress = required(v, "failure.max_stress", crit);
      check_positive("failure.max_stress", m.max_stress);
      break;
    default:
      break;
  }
  return m;
}

std::vector<StateFieldSpec> failure_state_fields(const FailureModel& m) {
  if (!m.active()) return {};
  return {{kDamageField, "1", 0.0}, {kFailedField, "1", 0.0, false}};
}

}  // namespace ballista
