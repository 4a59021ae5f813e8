#pragma once
// Failure criteria and erosion, per material (thesis seed 000 §6.4, eq. 6.5-6.14).
//
// Every registered model gets the `failure.*` parameters (appended by material_factory<Model>
// in material_adapter.hpp). With failure.criterion = none (the default) nothing is added: no
// state, no per-point work. Otherwise the material instance declares two state fields,
// `damage` (the criterion's measure, 0..1) and `failed` (0/1, never reset), and after every
// kernel call MaterialAdapter advances them with failure_update() from the stress at t_n and
// t_{n+1} and the kernel's PointResult; once failed, erode() replaces the stress (and, for
// zero_stress, the adapter resets F to F_n).
//
// Criteria (checked on the kernel's stress at t_{n+1}, before erosion):
//   johnson_cook_damage  d += Delta eps_p / eps_f,  failed at d >= 1                     (eq. 6.5)
//       eps_f = [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(max(edot*, 1))] [1 + D5 T*]
//       sigma* = tr(sigma) / (3 sigma_eq)  (0 if sigma_eq = 0), edot* = (Delta eps_p/dt)/edot_0
//       (G.R. Johnson & W.H. Cook, Eng. Fract. Mech. 21 (1985) 31-48, eq. 3 and 5.)
//   melt                 T* >= 1 (T* from PointResult::homologous_temperature)           (eq. 6.6)
//   tepla                (f/f_c)^2 + (eps_p/eps_p^f)^2 >= 1                                (eq. 6.8)
//       (F.L. Addessio & J.N. Johnson, J. Appl. Phys. 74 (1993) 1640, the TEPLA-F condition.)
//       Porosity: J2 flow is isochoric, so the growth term (1 - f) tr(D^p) of TEPLA vanishes; f is
//       the initial porosity f_0 plus optional strain-controlled nucleation (C.C. Chu &
//       A. Needleman, J. Eng. Mater. Technol. 102 (1980) 249: rate f_N/(s_N sqrt(2 pi))
//       exp(-((eps_p - eps_N)/s_N)^2/2) deps_p), integrated in closed form:
//         f(eps_p) = f_0 + f_N/2 [erf((eps_p - eps_N)/(s_N sqrt 2)) + erf(eps_N/(s_N sqrt 2))]
//       f is an indicator only: it does not soften the strength model (no Gurson yield surface).
//   drucker_stability    (sigma_{n+1} - sigma_n) : Delta eps^p < -tol                     (eq. 6.9)
//       (Drucker's postulate sigma_dot : D^p > 0, times dt^2; PointResult::drucker_product.)
//   max_stress           sigma_eq > sigma_max                                              (eq. 6.10)
//
// Erosion of a failed point (applied to sigma_{n+1} every step once failed):
//   none              the stress is left as the model computed it (damage still evolves)
//   allow_no_tension  sigma* = I1/3 I if I1 <= 0, else 0                                  (eq. 6.11)
//   allow_no_shear    sigma* = I1/3 I                                                     (eq. 6.12)
//   zero_stress       sigma* = 0 and F* = F_n (the deformation is frozen)           (eq. 6.13-6.14)
#include <cmath>
#include <limits>
#include <vector>

#include "materials/material.hpp"

namespace ballista {

/// State fields added by a failure criterion: the criterion's measure, 0..1 (1), and whether the
/// point has failed, 0 or 1, never reset (1). (Peridynamics also declares `damage`: the share of
/// broken bonds.)
inline constexpr FieldKey<double> kDamage{"damage"};
inline constexpr FieldKey<double> kFailed{"failed"};
/// Their names, for the state field specs and the models' by-name state access.
inline constexpr const char* kDamageField = kDamage.name();
inline constexpr const char* kFailedField = kFailed.name();

/// What a model's kernel fills in PointResult, declared by the model as
///   static constexpr bool kTracksPlasticStrain = true;  // delta_eqps, eqps, drucker_product
///   static constexpr bool kTracksTemperature = true;    // temperature, homologous_temperature
/// and read by MaterialAdapter (absent = false). Criteria that need what the model does not
/// track are rejected when the material is made.
struct ModelCapabilities {
  bool plastic_strain = false;
  bool temperature = false;
};

enum class FailureCriterion { None, JohnsonCookDamage, Melt, Tepla, DruckerStability, MaxStress };
enum class ErosionRule { None, AllowNoTension, AllowNoShear, ZeroStress };

/// The failure.* parameters of one material, checked by make_failure().
struct FailureModel {
  FailureCriterion criterion = FailureCriterion::None;
  ErosionRule erosion = ErosionRule::None;
  // Johnson-Cook damage (eq. 6.5).
  double d1 = 0, d2 = 0, d3 = 0, d4 = 0, d5 = 0;
  double reference_rate = 1.0;  ///< edot_0, 1/s
  // TEPLA-F (eq. 6.8).
  double initial_porosity = 0.0;    ///< f_0
  double critical_porosity = 1.0;   ///< f_c
  double fracture_strain = 1.0;     ///< eps_p^f
  double nucleation_porosity = 0.0; ///< f_N (0: no nucleation)
  double nucleation_strain = 0.3;   ///< eps_N
  double nucleation_stddev = 0.1;   ///< s_N
  // Maximum stress (eq. 6.10).
  double max_stress = std::numeric_limits<double>::infinity();  ///< sigma_max, Pa

  bool active() const { return criterion != FailureCriterion::None; }
};

/// failure.criterion, failure.erosion and the criteria's constants (appended to every model).
std::vector<ParamSpec> failure_param_specs();

/// Reads the failure.* values; throws ParamError naming the key: an unknown word, a criterion the
/// model cannot support (failure.criterion), a missing constant (e.g. failure.d1) or an
/// inconsistent one (failure.initial_porosity >= failure.critical_porosity).
FailureModel make_failure(const ParamValues& v, ModelCapabilities caps);

/// {damage, failed} if a criterion is set, else nothing.
std::vector<StateFieldSpec> failure_state_fields(const FailureModel& m);

/// TEPLA porosity f(eps_p): f_0 plus the closed-form integral of Chu-Needleman nucleation.
inline double tepla_porosity(const FailureModel& m, double eqps) {
  if (!(m.nucleation_porosity > 0.0)) return m.initial_porosity;
  const double k = 1.0 / (m.nucleation_stddev * std::sqrt(2.0));
  return m.initial_porosity + 0.5 * m.nucleation_porosity *
                                  (std::erf((eqps - m.nucleation_strain) * k) + std::erf(m.nucleation_strain * k));
}

/// Johnson-Cook failure strain eps_f(sigma*, edot_p, T*) of eq. 6.5 (Johnson & Cook 1985, eq. 3).
/// Below the reference rate the rate factor is 1: the logarithm would lower eps_f without bound
/// as edot_p -> 0 (Johnson & Cook fitted edot* >= 1; Uintah's JohnsonCookDamage also departs from
/// the logarithm there).
inline double jc_failure_strain(const FailureModel& m, double triaxiality, double eqps_rate, double tstar) {
  const double rate = std::max(eqps_rate / m.reference_rate, 1.0);
  return (m.d1 + m.d2 * std::exp(m.d3 * triaxiality)) * (1.0 + m.d4 * std::log(rate)) * (1.0 + m.d5 * tstar);
}

/// Round-off bound of the Drucker product (sigma_{n+1} - sigma_n) : Delta eps^p. Each stress
/// component of a kernel's update carries at most ~10-20 roundings of the larger stress magnitude,
/// so the difference carries <= k eps_mach (|sigma_n| + |sigma_{n+1}|) per component, and its
/// contraction with Delta eps^p (Cauchy-Schwarz, Frobenius norms) at most k eps_mach
/// (|sigma_n| + |sigma_{n+1}|) |Delta eps^p| with |Delta eps^p| = sqrt(3/2) Delta eps_p for a
/// deviatoric flow. k = 64 covers that with margin; a real softening modulus h < 0 gives a product
/// h Delta eps_p^2, detected once |h| Delta eps_p > ~2e-13 |sigma| (perfect plasticity, h = 0,
/// sits exactly on the boundary and must not trigger).
inline double drucker_tolerance(const Mat3& sigma_old, const Mat3& sigma_new, double delta_eqps) {
  constexpr double k = 64.0 * std::numeric_limits<double>::epsilon();
  return k * (frobenius(sigma_old) + frobenius(sigma_new)) * std::sqrt(1.5) * delta_eqps;
}

/// Advances `damage` and `failed` of one point over a step from the kernel's unrotated stress at
/// t_n and t_{n+1} and its PointResult. Returns true if the point is failed at t_{n+1}.
inline bool failure_update(const FailureModel& m, const Mat3& sigma_old, const Mat3& sigma_new,
                           const PointResult& r, double dt, double& damage, double& failed) {
  if (failed != 0.0) return true;  // failure is permanent
  double measure = 0.0;            // the criterion's measure at t_{n+1}; failed at >= 1
  bool now = false;
  switch (m.criterion) {
    case FailureCriterion::None:
      return false;
    case FailureCriterion::JohnsonCookDamage: {
      measure = damage;
      if (r.delta_eqps > 0.0) {
        const double q = von_mises(sigma_new);
        const double triax = q > 0.0 ? trace(sigma_new) / (3.0 * q) : 0.0;
        const double tstar = m.d5 != 0.0 ? r.homologous_temperature : 0.0;
        const double ef = jc_failure_strain(m, triax, r.delta_eqps / dt, tstar);
        // eps_f <= 0 (possible with D1 < 0 or a large T*): any plastic increment fails the point.
        measure = ef > 0.0 ? damage + r.delta_eqps / ef : 1.0;
      }
      now = measure >= 1.0;
      break;
    }
    case FailureCriterion::Melt:
      measure = r.homologous_temperature;
      now = measure >= 1.0;
      break;
    case FailureCriterion::Tepla: {
      const double f = tepla_porosity(m, r.eqps) / m.critical_porosity;
      const double e = r.eqps / m.fracture_strain;
      measure = f * f + e * e;
      now = measure >= 1.0;
      break;
    }
    case FailureCriterion::DruckerStability:
      now = r.drucker_product < -drucker_tolerance(sigma_old, sigma_new, r.delta_eqps);
      measure = now ? 1.0 : 0.0;
      break;
    case FailureCriterion::MaxStress: {
      const double q = von_mises(sigma_new);
      measure = q / m.max_stress;
      now = q > m.max_stress;
      break;
    }
  }
  // damage is monotone: accumulated (JC) or the largest measure so far, capped at 1.
  if (m.criterion == FailureCriterion::JohnsonCookDamage)
    damage = std::min(measure, 1.0);
  else if (measure > damage)
    damage = std::min(measure, 1.0);
  if (now) {
    damage = 1.0;
    failed = 1.0;
  }
  return now;
}

/// True for a point already failed (`failed` flag of its state) whose erosion is zero_stress: its
/// stress stays zero and its deformation and state are frozen at F_n, so nothing a material kernel
/// computes for it is kept.
inline bool frozen_when_failed(const FailureModel& m, double failed) {
  return failed != 0.0 && m.erosion == ErosionRule::ZeroStress;
}

/// Eroded stress sigma* of a failed point (eq. 6.11-6.13); the rule applies to the Cauchy stress
/// in any frame (both results are isotropic). ZeroStress also freezes F (done by the adapter).
inline void erode(ErosionRule rule, Mat3& sigma) {
  switch (rule) {
    case ErosionRule::None:
      return;
    case ErosionRule::AllowNoTension:
    case ErosionRule::AllowNoShear: {
      const double i1 = trace(sigma);
      const double mean = (rule == ErosionRule::AllowNoTension && i1 > 0.0) ? 0.0 : i1 / 3.0;
      sigma = Mat3{};
      sigma(0, 0) = sigma(1, 1) = sigma(2, 2) = mean;
      return;
    }
    case ErosionRule::ZeroStress:
      sigma = Mat3{};
      return;
  }
}

}  // namespace ballista
