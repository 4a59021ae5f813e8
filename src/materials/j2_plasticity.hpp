#pragma once
// von Mises (J2) plasticity, hypoelastic in the unrotated frame, with isotropic hardening (linear,
// power law or Voce: hardening.hpp), optional linear kinematic hardening, and an equation of state
// for the pressure (eos.hpp).
//
// Elastic predictor (thesis seed 000 §2.3, eq. 2.6: D_bar = R^T D R with R from F = R U; D_bar
// approximates the Hencky strain rate for small elastic strain), split into deviator and pressure
// as every EOS-composed model does (eos.hpp): with eps = D_bar dt, sigma_bar_n = s_n - p_n I,
//   s_trial = s_n + 2G dev(eps)
// Plastic corrector: radial return of Simo & Hughes, Computational Inelasticity (1998), §3.3,
// Box 3.1, on f = sqrt(3/2)|s - alpha| - sigma_y(eps_p) (j2_return.hpp): closed form for linear
// isotropic hardening, safeguarded Newton for power_law and voce. Backstress (Prager/Ziegler):
// Delta alpha = (2/3) H_k Delta eps^p, stored in the unrotated frame, so it needs no objective
// rate: the adapter's rotation makes it objective by construction, as for the stress.
// Pressure: p_{n+1} from eos_update (linear: p_n - K tr(eps), the hypoelastic bulk response of the
// original model; mie_gruneisen: energy-consistent closed form). Plastic flow is deviatoric.
//
// H is the plastic (not the tangent) modulus: sigma_y(eps_p) = sigma_y0 + H eps_p, so in uniaxial
// stress the elastic-plastic tangent is E (H + H_k) / (E + H + H_k). The "linear hardening
// modulus 100 MPa" of the Taylor-anvil benchmark (verification CATALOGUE B6) is this H.
//
// State: eqps always; backstress_11 ... backstress_12 (6 fields) only if kinematic_modulus > 0;
// energy_density only with eos.type mie_gruneisen. The default deck (linear law, no kinematic
// hardening, linear EOS) therefore keeps the original single state field and its fast path.
#include <cmath>

#include "materials/elastic_constants.hpp"
#include "materials/hardening.hpp"
#include "materials/j2_elastic_eos.hpp"
#include "materials/j2_return.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

namespace j2_detail {
/// Order of the six independent components of a symmetric tensor in the state (and the tangent).
inline constexpr int kSymI[6] = {0, 1, 2, 1, 0, 0};
inline constexpr int kSymJ[6] = {0, 1, 2, 2, 2, 1};
inline constexpr const char* kBackstressNames[6] = {"backstress_11", "backstress_22", "backstress_33",
                                                    "backstress_23", "backstress_13", "backstress_12"};
}  // namespace j2_detail

struct J2Plasticity {
  // Kernel of the deck model j2_plasticity (registered in j2_plasticity.cpp).
  static constexpr const char* kName = "j2_plasticity";
  static constexpr bool kTracksPlasticStrain = true;  // fills PointResult eqps, delta_eqps, drucker_product
  /// density, bulk, shear, eos and energy_slot: J2ElasticEos (shared with johnson_cook).
  struct Params : J2ElasticEos {
    IsotropicHardening hardening;  ///< sigma_y(eps_p)
    double h_kin = 0;       ///< kinematic (Prager) modulus H_k, Pa
    bool kinematic = false; ///< H_k > 0: six backstress fields follow eqps in the state
    bool fast = false;      ///< default configuration: update_fast
  };

  static std::vector<ParamSpec> param_specs() {
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<ParamSpec> s = elastic_param_specs();
    s.push_back({"yield_stress", "Pa",
                 "initial yield stress sigma_y0 in uniaxial tension (= sqrt(3) x yield in shear)", true,
                 0.0, 0.0, inf, true, false});
    s.push_back({"hardening_modulus", "Pa",
                 "linear isotropic hardening (plastic) modulus H: sigma_y = sigma_y0 + H eps_p (linear, voce)", false,
                 0.0, 0.0, inf, false, false});
    for (ParamSpec& h : hardening_param_specs()) s.push_back(std::move(h));
    s.push_back({"kinematic_modulus", "Pa",
                 "linear kinematic (Prager) hardening modulus H_k: d alpha = (2/3) H_k d eps^p", false, 0.0, 0.0,
                 inf, false, false});
    for (ParamSpec& e : eos_param_specs()) s.push_back(std::move(e));
    return s;
  }

  static Params make(const ParamValues& v) {
    Params p;
    p.read_elastic(v);
    p.hardening = make_hardening(v);
    p.h_kin = v.number_or("kinematic_modulus", 0.0);
    if (!(p.h_kin >= 0.0)) throw ParamError("kinematic_modulus", "kinematic_modulus must be >= 0");
    p.kinematic = p.h_kin > 0.0;
    p.eos = make_eos(v, p.bulk, p.density);
    if (p.eos.kind == Eos::Kind::MieGruneisen) p.energy_slot = p.kinematic ? 7 : 1;
    p.fast = p.hardening.law == HardeningLaw::Linear && !p.kinematic && p.eos.kind == Eos::Kind::Linear &&
             p.eos.p_min == -std::numeric_limits<double>::infinity();
    return p;
  }

  // Verification hooks (MaterialFactory).
  static ParamValues example_params() {
    return {{"density", 8930.0}, {"youngs_modulus", 117e9}, {"poisson_ratio", 0.35}, {"yield_stress", 400e6},
            {"hardening_modulus", 100e6}};
  }
  /// Elastic reduction: a yield stress no A1 path can reach.
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"yield_stress", 1e30}};
  }
  /// J2 with linear isotropic (H_iso) and linear kinematic (H_kin) hardening.
  static ParamValues reduce_to_j2(double rho, double K, double G, double sy, double h_iso, double h_kin) {
    return {{"density", rho},       {"bulk_modulus", K},          {"shear_modulus", G},
            {"yield_stress", sy},   {"hardening_modulus", h_iso}, {"kinematic_modulus", h_kin}};
  }

  /// All state fields the model can have (registry, `ballista info`).
  static std::vector<StateFieldSpec> state_fields() {
    std::vector<StateFieldSpec> f{{"eqps", "1", 0.0}};
    for (const char* n : j2_detail::kBackstressNames) f.push_back({n, "Pa", 0.0});
    f.push_back(eos_state_field());
    return f;
  }
  /// The fields of one parameter set: eqps [, backstress x 6] [, energy_density].
  static std::vector<StateFieldSpec> state_fields(const Params& p) {
    std::vector<StateFieldSpec> f{{"eqps", "1", 0.0}};
    if (p.kinematic)
      for (const char* n : j2_detail::kBackstressNames) f.push_back({n, "Pa", 0.0});
    if (p.energy_slot >= 0) f.push_back(eos_state_field());
    return f;
  }

  static void update(const Params& p, const PointKinematics& k, Mat3& sigma, double* state, PointResult& res) {
    if (p.fast && !res.tangent) return update_fast(p, k, sigma, state[0], res);
    using j2_detail::kSymI;
    using j2_detail::kSymJ;
    const double G = p.shear;
    const Mat3 eps = k.dt * k.D_bar;
    double p_old;
    const Mat3 s_old = split_pressure(sigma, p_old);
    Mat3 s = deviatoric_trial(s_old, eps, G);
    double& eqps = state[0];
    Mat3 alpha;
    if (p.kinematic)
      for (int c = 0; c < 6; ++c) alpha(kSymI[c], kSymJ[c]) = alpha(kSymJ[c], kSymI[c]) = state[1 + c];

    J2Return r = j2_trial(s, p.kinematic ? &alpha : nullptr, p.hardening.value(eqps));
    DevTangent tangent = elastic_tangent(G);
    if (r.plastic) {
      const double c = 3.0 * G + p.h_kin;
      if (p.hardening.law == HardeningLaw::Linear) {
        // Closed form (Simo & Hughes Box 3.1 step 4 with combined hardening).
        r.delta_eqps = r.f_trial / (c + p.hardening.modulus);
        r.slope = p.hardening.modulus;
      } else {
        const IsotropicHardening& h = p.hardening;
        const double e0 = eqps;
        r.delta_eqps = j2_solve_increment(
            r.q_trial, r.f_trial, c, [&](double d) { return FlowStress{h.value(e0 + d), h.slope(e0 + d)}; },
            r.slope);
      }
      const Mat3 dep = j2_apply(r, s, p.kinematic ? &alpha : nullptr, G, p.h_kin);
      res.plastic_work_density = p.hardening.integral(eqps, r.delta_eqps);
      res.delta_eqps = r.delta_eqps;
      res.drucker_product = ddot(s - s_old, dep);  // (sigma_{n+1} - sigma_n) : Delta eps^p (dep traceless)
      eqps += r.delta_eqps;
      if (p.kinematic)
        for (int c = 0; c < 6; ++c) state[1 + c] = alpha(kSymI[c], kSymJ[c]);
      if (res.tangent) tangent = plastic_tangent(r, G, p.h_kin);
    }
    res.eqps = eqps;
    double scratch = 0.0;
    double& energy = p.energy_slot >= 0 ? state[p.energy_slot] : scratch;
    sigma = j2_compose_eos(p.eos, k, eps, p_old, s_old, s, energy, p.energy_slot >= 0, tangent, res);
  }

  /// The default configuration (linear isotropic hardening, no backstress, linear EOS without
  /// tension cutoff), used by the MPM hot loop: the same algebra as update() with the pressure kept
  /// inside the stress (sigma_trial = sigma_n + lambda tr(eps) I + 2G eps, then the radial return
  /// of the deviator), about 10 % cheaper per point than the general path.
  static void update_fast(const Params& p, const PointKinematics& k, Mat3& sigma, double& eqps, PointResult& res) {
    const double G = p.shear, H = p.hardening.modulus;
    const double lam = p.bulk - 2.0 * G / 3.0;
    sigma += (k.dt * 2.0 * G) * k.D_bar;
    const double iso = k.dt * lam * trace(k.D_bar);
    sigma(0, 0) += iso; sigma(1, 1) += iso; sigma(2, 2) += iso;
    const double mean = trace(sigma) / 3.0;
    Mat3 s = sigma;
    s(0, 0) -= mean; s(1, 1) -= mean; s(2, 2) -= mean;
    const double q_trial = std::sqrt(1.5 * ddot(s, s));
    const double f = q_trial - (p.hardening.yield0 + H * eqps);
    if (f > 0.0) {  // false for a NaN trial, which then propagates
      const double de = f / (3.0 * G + H);
      sigma += (-3.0 * G * de / q_trial) * s;  // s_{n+1} = (1 - 3G de/q_tr) s_tr
      res.plastic_work_density = (p.hardening.yield0 + H * (eqps + 0.5 * de)) * de;  // exact int sigma_y
      res.delta_eqps = de;
      // (sigma_{n+1} - sigma_n) : Delta eps^p with Delta eps^p = (3/2)(de/q_tr) s_tr (traceless) and
      // sigma_{n+1} - sigma_n = 2G eps + lambda tr(eps) I - 3G (de/q_tr) s_tr, s_tr : s_tr = (2/3) q_tr^2:
      // = 3G de [dt (D_bar : s_tr)/q_tr - de].
      res.drucker_product = 3.0 * G * de * (k.dt * ddot(k.D_bar, s) / q_trial - de);
      eqps += de;
    }
    res.eqps = eqps;
  }

  /// update_fast for kLanes points (material_lanes.hpp), bitwise the same lane by lane: the plastic
  /// correction is computed on every lane and kept where the trial stress is beyond yield.
  static bool lanes_apply(const Params& p) { return p.fast; }
  static void update_lanes(const Params& p, const LaneKinematics& k, Mat3L& sigma, Lane* state, Lane& plastic_work) {
    const double G = p.shear, H = p.hardening.modulus;
    const double lam = p.bulk - 2.0 * G / 3.0;
    sigma = sigma + (k.dt * 2.0 * G) * k.D_bar;
    const Lane iso = k.dt * lam * trace(k.D_bar);
    sigma.a[0] += iso; sigma.a[4] += iso; sigma.a[8] += iso;
    const Lane mean = trace(sigma) / 3.0;
    Mat3L s = sigma;
    s.a[0] -= mean; s.a[4] -= mean; s.a[8] -= mean;
    const Lane q_trial = lane_sqrt(1.5 * ddot(s, s));
    Lane& eqps = state[0];
    const Lane f = q_trial - (p.hardening.yield0 + H * eqps);
    const LaneMask plastic = f > 0.0;
    if (!any(plastic)) return;
    const Lane de = f / (3.0 * G + H);
    const Mat3L corrected = sigma + (-3.0 * G * de / q_trial) * s;
    for (int e = 0; e < 9; ++e) sigma.a[e] = select(plastic, corrected.a[e], sigma.a[e]);
    plastic_work = select(plastic, (p.hardening.yield0 + H * (eqps + 0.5 * de)) * de, plastic_work);
    eqps = select(plastic, eqps + de, eqps);
  }

  /// Dilatational wave speed of the elastic part (J2ElasticEos::wave_speed).
  static double wave_speed(const Params& p, const double* state, double J) { return p.wave_speed(state, J); }
};

}  // namespace ballista
