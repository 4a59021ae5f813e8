#pragma once
// Sandstone geomodel: Ballista's equivalent of the Arenisca model of the thesis seed 000
// (§3.2, §4.1.1.3-4.1.1.4, §8.1.7): a two-surface plasticity model for porous, fluid-filled rock.
//   - Limit surface: linear Drucker-Prager, sqrt(J2) = FSLOPE (PEAKI1 - I1) (eq. 4.2-4.4), or the
//     pressure-saturating nonlinear form Ff = a1 - a3 exp(a2 I1) - a4 I1 (§8.1.7's "nonlinear
//     Drucker-Prager"); fslope = 0 reduces it to von Mises (J2) with sqrt(J2) = stren.
//   - Elliptical cap of eccentricity cap_ratio, at X on the hydrostat given by the crush curve of
//     eq. 4.5-4.6 in the plastic volumetric strain evp: pore collapse moves it out (hardening),
//     dilatation pulls it back (softening by porosity growth).
//   - Non-associative flow: the isotropic part of the flow direction is scaled by flow_beta.
//   - Nonlinear elasticity: K = B0 + B1 exp(-B2/|I1'|) in compression (B0 in tension), G constant,
//     or from a pressure-dependent Poisson ratio (Arenisca 3 forms; Homel et al. 2016 §2.2).
//   - Pore fluid (undrained): saturated bulk modulus by Biot-Gassmann, and the pore pressure from
//     pore collapse as an isotropic backstress I1' = I1 + 3 pf (geomodel_surface.hpp).
//   - Optional rate dependence: Duvaut-Lions overstress (Simo & Hughes, Computational
//     Inelasticity, 1998, §2.7.3): sigma = (sigma_trial + (dt/tau) sigma_inviscid)/(1 + dt/tau) per
//     substep, tau = T1 (strain rate x 1 s)^(-T2).
// The formulas and their sources are in geomodel_surface.hpp; the return algorithm (transformed-
// space closest point + consistency bisection, Homel, Guilkey & Brannon, Comput. Mech. 56 (2015)
// 565-584) in geomodel_return.hpp and below.
//
// Kinematics as every hypoelastic Ballista model: the stress is integrated in the unrotated frame
// with the midpoint strain increment eps = D_bar dt (material_adapter.hpp). The step is split into
// n substeps (at most max_substeps) so that each trial-stress increment is a fraction of the yield
// surface's size and the nonlinear bulk modulus changes little within one.
//
// Limits (docs/materials.md): no algorithmic tangent (explicit solvers do not need one; A6 tangent
// is not applicable); elastic compression of the pore fluid stiffens the bulk response but only
// the pore pressure from pore collapse shifts the yield surface (Homel et al.'s simplification);
// no third-invariant (Lode) dependence, no shear softening or damage (thesis §8.1.6-8.1.7).
#include <cmath>
#include <limits>
#include <vector>

#include "core/illinois.hpp"
#include "materials/geomodel_coupled_return.hpp"
#include "materials/geomodel_return.hpp"
#include "materials/geomodel_surface.hpp"
#include "materials/material_adapter.hpp"

namespace ballista {

struct Geomodel {
  static constexpr const char* kName = "geomodel";
  static constexpr bool kTracksPlasticStrain = true;

  struct Params {
    double density = 0;
    double B0 = 0, B1 = 0, B2 = 1;  ///< bulk modulus law, Pa
    double G0 = 0;                  ///< shear modulus, Pa
    bool poisson = false;           ///< shear modulus from nu = nu_low + nu_gain exp(-B2/|I1'|)
    double nu_low = 0, nu_gain = 0;
    GeoLimit limit;
    double cap_ratio = 0.5;
    GeoCrushCurve crush;
    double beta = 1.0;              ///< non-associativity
    double Kf = 0, pf0 = 0, Km = 0; ///< pore fluid, initial pore pressure, matrix modulus (Pa)
    /// Plastic volumetric strain beyond which the pore fluid has cavitated (pf = 0): the rock is
    /// then drained; below it the fluid is held and the bulk modulus is Biot-Gassmann's.
    double ev_cavitation = 0;
    double T1 = 0, T2 = 0;          ///< Duvaut-Lions relaxation time (s) and rate exponent
    int max_substeps = 256;
    // State layout: eqps, plastic_volumetric_strain, substeps, [porosity, cap_i1], [pore_pressure].
    int slot_porosity = -1, slot_cap = -1, slot_pore_pressure = -1;

    bool fluid() const { return Kf > 0.0; }
    bool hardening() const { return (crush.active() && !crush.fixed) || fluid(); }
  };

  static std::vector<ParamSpec> param_specs() {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {
        {"density", "kg/m^3", "reference mass density rho0", true, 0.0, 0.0, inf, true, false},
        {"bulk_modulus", "Pa", "B0: drained bulk modulus at low pressure and in tension", true, 0.0, 0.0, inf, true,
         false},
        {"bulk_modulus_gain", "Pa", "B1: extra bulk modulus at high pressure, K = B0 + B1 exp(-B2/|I1'|)", false, 0.0,
         0.0, inf, false, false},
        {"bulk_modulus_i1_scale", "Pa", "B2: |I1| scale of the bulk modulus transition", false, 1.0, 0.0, inf, true,
         false},
        {"shear_modulus", "Pa", "G0: shear modulus (replaced by the Poisson-ratio law if that is given)", true, 0.0,
         0.0, inf, true, false},
        {"poisson_ratio_low", "1", "G1: drained Poisson ratio at low pressure (with poisson_ratio_gain)", false, nan,
         -1.0, 0.5, true, true},
        {"poisson_ratio_gain", "1", "G2: nu = G1 + G2 exp(-B2/|I1'|), G = 1.5 K (1 - 2 nu)/(1 + nu)", false, nan, 0.0,
         0.5, false, true},
        {"peak_i1", "Pa", "PEAKI1: tensile vertex of the limit surface on the I1 axis (required if fslope > 0)", false,
         nan, -inf, inf, false, false},
        {"fslope", "1", "FSLOPE: slope d sqrt(J2)/d(-I1) of the limit surface at the vertex (0: von Mises)", false,
         0.0, 0.0, inf, false, false},
        {"stren", "Pa", "STREN: high-pressure limit of sqrt(J2) (nonlinear form); with fslope 0 the von Mises sqrt(J2)",
         false, nan, 0.0, inf, true, false},
        {"yslope", "1", "YSLOPE: high-pressure slope of the nonlinear limit surface", false, 0.0, 0.0, inf, false,
         false},
        {"cap_ratio", "1", "CR: cap eccentricity, I1 radius over sqrt(J2) radius of the elliptical cap", false, 0.5,
         0.0, inf, true, false},
        {"crush_p0", "Pa", "P0: cap position X (an I1, negative) at zero plastic volumetric strain", false, nan, -inf,
         0.0, false, true},
        {"crush_p1", "1/Pa", "P1: crush-curve rate, X = P0 + ln(1 + evp/P3)/P1 in compaction", false, nan, 0.0, inf,
         true, false},
        {"crush_p3", "1", "P3: -ln(1 - initial porosity), the plastic volume strain of full crush (0: no cap)", false,
         0.0, 0.0, inf, false, false},
        {"cap_evolution", "", "crush_curve: the cap follows the crush curve; fixed: the cap stays at P0", false, 0.0,
         -inf, inf, false, false, {"crush_curve", "fixed"}, "crush_curve"},
        {"flow_beta", "1", "non-associativity: isotropic part of the plastic flow scaled by beta (1: associative)",
         false, 1.0, 0.0, 1.0, true, false},
        {"fluid_bulk_modulus", "Pa", "Kf: pore-fluid bulk modulus (0: drained)", false, 0.0, 0.0, inf, false, false},
        {"initial_pore_pressure", "Pa", "pf0: initial pore-fluid pressure", false, 0.0, 0.0, inf, false, false},
        {"matrix_bulk_modulus", "Pa", "Km: grain (matrix) bulk modulus for Biot-Gassmann (default B0 + B1)", false, nan,
         0.0, inf, true, false},
        {"relaxation_time", "s", "T1: Duvaut-Lions relaxation time (0: rate independent)", false, 0.0, 0.0, inf, false,
         false},
        {"relaxation_rate_exponent", "1", "T2: tau = T1 (equivalent strain rate x 1 s)^(-T2)", false, 0.0, 0.0, inf,
         false, false},
        {"max_substeps", "1", "most substeps per step", false, 256.0, 1.0, 1e5, false, false},
    };
  }

  static Params make(const ParamValues& v) {
    Params p;
    auto num = [&](const char* k, double d) { return v.number_or(k, d); };
    p.density = v.at("density");
    p.B0 = v.at("bulk_modulus");
    p.B1 = num("bulk_modulus_gain", 0.0);
    p.B2 = num("bulk_modulus_i1_scale", 1.0);
    p.G0 = v.at("shear_modulus");
    const bool g1 = v.given("poisson_ratio_low"), g2 = v.given("poisson_ratio_gain");
    if (g1 != g2)
      throw ParamError(g1 ? "poisson_ratio_gain" : "poisson_ratio_low",
                       "poisson_ratio_low and poisson_ratio_gain go together");
    p.poisson = g1;
    if (p.poisson) {
      p.nu_low = v.at("poisson_ratio_low");
      p.nu_gain = v.at("poisson_ratio_gain");
      if (!(p.nu_low + p.nu_gain < 0.5))
        throw ParamError("poisson_ratio_gain", "poisson_ratio_low + poisson_ratio_gain must be < 0.5");
    }
    // Limit surface.
    const double fslope = num("fslope", 0.0), stren = num("stren", NAN), yslope = num("yslope", 0.0);
    const bool peak_given = v.given("peak_i1");
    if (fslope == 0.0) {
      if (std::isnan(stren))
        throw ParamError("stren", "fslope 0 is von Mises: give stren, the yield stress in shear sqrt(J2)");
      if (peak_given) throw ParamError("peak_i1", "peak_i1 needs fslope > 0 (a von Mises surface has no vertex)");
    } else {
      if (!peak_given) throw ParamError("peak_i1", "fslope > 0 needs peak_i1, the tensile vertex of the limit surface");
      if (!std::isnan(stren)) {
        const double peak = v.at("peak_i1");
        if (!(yslope < fslope)) throw ParamError("yslope", "yslope must be smaller than fslope");
        if (!(stren > yslope * peak)) throw ParamError("stren", "stren must exceed yslope * peak_i1");
      } else if (yslope != 0.0) {
        throw ParamError("yslope", "yslope needs stren (the nonlinear limit surface)");
      }
    }
    p.limit = GeoLimit::make(peak_given ? v.at("peak_i1") : INFINITY, fslope, stren, yslope);
    // Cap and crush curve.
    p.cap_ratio = num("cap_ratio", 0.5);
    p.crush.p3 = num("crush_p3", 0.0);
    if (p.crush.active()) {
      if (!v.given("crush_p0")) throw ParamError("crush_p0", "crush_p3 > 0 (porosity) needs crush_p0, the cap's I1");
      if (!v.given("crush_p1")) throw ParamError("crush_p1", "crush_p3 > 0 (porosity) needs crush_p1");
      p.crush.p0 = v.at("crush_p0");
      p.crush.p1 = v.at("crush_p1");
      if (!(p.crush.p0 < 0.0)) throw ParamError("crush_p0", "crush_p0 must be < 0 (compression)");
      if (!(p.crush.p0 < p.limit.peak_i1)) throw ParamError("crush_p0", "crush_p0 must lie below peak_i1");
    }
    p.crush.fixed = v.choice("cap_evolution", "crush_curve") == "fixed";
    p.beta = num("flow_beta", 1.0);
    // Pore fluid.
    p.Kf = num("fluid_bulk_modulus", 0.0);
    p.pf0 = num("initial_pore_pressure", 0.0);
    p.Km = num("matrix_bulk_modulus", p.B0 + p.B1);
    if (p.fluid()) {
      if (!p.crush.active())
        throw ParamError("fluid_bulk_modulus", "a pore fluid needs porosity: give crush_p3 > 0 (and the crush curve)");
      if (!(p.Km > p.Kf)) throw ParamError("matrix_bulk_modulus", "matrix_bulk_modulus must exceed fluid_bulk_modulus");
      if (!(p.Km >= p.B0 + p.B1))
        throw ParamError("matrix_bulk_modulus", "matrix_bulk_modulus must be >= bulk_modulus + bulk_modulus_gain");
    } else if (p.pf0 != 0.0) {
      throw ParamError("initial_pore_pressure", "initial_pore_pressure needs fluid_bulk_modulus > 0");
    }
    p.T1 = num("relaxation_time", 0.0);
    p.T2 = num("relaxation_rate_exponent", 0.0);
    p.max_substeps = static_cast<int>(num("max_substeps", 256.0));
    if (p.fluid()) {
      // Plastic dilatation at which the pore pressure reaches zero (geo_pore_pressure with pf = 0).
      const double phi0 = p.crush.initial_porosity();
      p.ev_cavitation = std::log((1.0 - phi0) * std::exp(p.pf0 / p.Km) + phi0 * std::exp(p.pf0 / p.Kf));
    }
    int slot = 3;
    if (p.crush.active()) {
      p.slot_porosity = slot++;
      p.slot_cap = slot++;
    }
    if (p.fluid()) p.slot_pore_pressure = slot++;
    return p;
  }

  // ---- Verification hooks (MaterialFactory) ----
  /// A saturated Berea-like sandstone with every feature on (A6 objectivity).
  static ParamValues example_params() {
    return {{"density", 2300.0},          {"bulk_modulus", 10e9},        {"bulk_modulus_gain", 8e9},
            {"bulk_modulus_i1_scale", 3e8}, {"shear_modulus", 7e9},      {"peak_i1", 20e6},
            {"fslope", 0.45},             {"stren", 150e6},             {"yslope", 0.05},
            {"cap_ratio", 0.6},           {"crush_p0", -300e6},         {"crush_p1", 2e-9},
            {"crush_p3", 0.2},            {"flow_beta", 0.8},           {"fluid_bulk_modulus", 2.2e9},
            {"initial_pore_pressure", 0.0}, {"matrix_bulk_modulus", 37e9}};
  }
  /// Elastic: a von Mises surface no A1 path reaches, no cap.
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"stren", 1e30}};
  }
  /// von Mises with sqrt(J2) = sigma_y/sqrt3; the model has no strain hardening of the limit surface.
  static ParamValues reduce_to_j2(double rho, double K, double G, double sy, double h_iso, double h_kin) {
    if (h_iso != 0.0 || h_kin != 0.0) return {};
    return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}, {"stren", sy / std::sqrt(3.0)}};
  }
  static ParamValues reduce_to_geo(const GeoReduction& g) {
    ParamValues v{{"density", g.density}, {"bulk_modulus", g.bulk}, {"shear_modulus", g.shear},
                  {"peak_i1", g.peak_i1}, {"fslope", g.fslope}, {"flow_beta", g.flow_beta}};
    if (g.p3 > 0.0) {
      v["cap_ratio"] = g.cap_ratio;
      v["crush_p0"] = g.p0;
      v["crush_p1"] = g.p1;
      v["crush_p3"] = g.p3;
      v.choices["cap_evolution"] = g.fixed_cap ? "fixed" : "crush_curve";
    }
    if (g.fluid_bulk > 0.0) {
      v["fluid_bulk_modulus"] = g.fluid_bulk;
      v["initial_pore_pressure"] = g.pore_pressure0;
    }
    return v;
  }

  // ---- State ----
  static std::vector<StateFieldSpec> state_fields() {
    return {{"eqps", "1", 0.0},         {"plastic_volumetric_strain", "1", 0.0}, {"substeps", "1", 0.0, false},
            {"porosity", "1", 0.0},     {"cap_i1", "Pa", 0.0},                   {"pore_pressure", "Pa", 0.0}};
  }
  static std::vector<StateFieldSpec> state_fields(const Params& p) {
    std::vector<StateFieldSpec> f{{"eqps", "1", 0.0}, {"plastic_volumetric_strain", "1", 0.0}, {"substeps", "1", 0.0, false}};
    if (p.crush.active()) {
      f.push_back({"porosity", "1", p.crush.initial_porosity()});
      f.push_back({"cap_i1", "Pa", p.crush.p0});
    }
    if (p.fluid()) f.push_back({"pore_pressure", "Pa", p.pf0});
    return f;
  }

  // ---- Constitutive pieces ----
  /// Pore pressure at plastic volumetric strain evp (0 when drained).
  /// `guess` >= 0: a nearby value to start the Newton solve from (e.g. the state's last value).
  /// `dpf_devp`, if given, receives the derivative dpf/devp (0 drained or cavitated).
  static double pore_pressure(const Params& p, double evp, double guess = -1.0, double* dpf_devp = nullptr) {
    if (dpf_devp) *dpf_devp = 0.0;
    if (!p.fluid() || evp >= p.ev_cavitation) return 0.0;  // drained, or cavitated
    return geo_pore_pressure(evp, p.crush.initial_porosity(), p.pf0, p.Kf, p.Km, std::max(guess, 0.0), dpf_devp);
  }
  /// The yield surface (in effective I1) at plastic volumetric strain evp.
  /// `kappa_guess`: a nearby branch point to start its Newton solve from (same answer).
  static GeoSurface surface(const Params& p, double evp,
                            double kappa_guess = std::numeric_limits<double>::quiet_NaN()) {
    GeoSurface s;
    s.limit = p.limit;
    if (p.crush.active()) {
      s.X = p.crush.cap(evp);
      s.kappa = geo_cap_kappa(p.limit, p.cap_ratio, s.X, kappa_guess);
    }
    return s;
  }
  /// Tangent elastic moduli at effective I1 `i1e` (Arenisca 3 forms, Homel et al. 2016 §2.2):
  /// drained K = B0 + B1 exp(-B2/|I1'|) in compression, B0 in tension; saturated by Biot-Gassmann
  /// while the pore fluid is held (not cavitated: evp <= ev_cavitation), elastic loading included.
  static void moduli(const Params& p, double i1e, double evp, double& K, double& G) {
    const double e = (i1e < 0.0 && (p.B1 > 0.0 || p.poisson)) ? std::exp(p.B2 / i1e) : 0.0;  // exp(-B2/|I1'|)
    const double Kd = p.B0 + p.B1 * e;
    G = p.G0;
    if (p.poisson) {
      const double nu = p.nu_low + p.nu_gain * e;
      G = 1.5 * Kd * (1.0 - 2.0 * nu) / (1.0 + nu);
    }
    K = (p.fluid() && evp <= p.ev_cavitation) ? biot_gassmann(Kd, p.Km, p.Kf, p.crush.porosity(evp)) : Kd;
  }

  /// The yield function sqrt(J2) - Ff Fc at effective I1 `i1e` for cap position X, as
  /// GeoSurface::f, without solving for kappa unless the point is under the cap: since
  /// k - X - CR Ff(k) increases with k, I1' >= kappa exactly when I1' - X >= CR Ff(I1').
  /// `ff_out`, if given, receives p.limit.value(i1e) where it was evaluated (else it is left as is).
  static double yield_value(const Params& p, double X, double i1e, double rj2, double* ff_out = nullptr) {
    const double peak = p.limit.peak_i1;
    if (i1e > peak) return rj2 + (i1e - peak);
    if (i1e < X) return rj2 + (X - i1e);
    const double ff_raw = p.limit.value(i1e);
    if (ff_out) *ff_out = ff_raw;
    const double ff = std::max(0.0, ff_raw);
    if (!std::isfinite(X) || i1e - X >= p.cap_ratio * ff) return rj2 - ff;
    const double kappa = geo_cap_kappa(p.limit, p.cap_ratio, X);
    const double u = (kappa - i1e) / (kappa - X);
    return rj2 - ff * std::sqrt(std::max(0.0, 1.0 - u * u));
  }

  /// True only where yield_value(p, X, i1e, rj2) > 0 is certainly false, decided without the
  /// limit surface's exponential (GeoLimit::bounds): I1' within [X, PEAKI1], sqrt(J2) at most the
  /// lower bound of Ff, and I1' - X at least CR times its upper bound (so yield_value takes its
  /// sqrt(J2) - Ff branch, outside the cap region). False for NaN. A point inside the surface by
  /// more than the bounds' gap passes; the others are for yield_value to decide.
  static bool certainly_elastic(const Params& p, double X, double i1e, double rj2) {
    if (!(i1e >= X && i1e <= p.limit.peak_i1)) return false;
    double lo, hi;
    p.limit.bounds(i1e, lo, hi);
    // rj2 <= lo <= max(0, Ff) = ff gives rj2 - ff <= 0; ff <= max(0, hi), so CR ff <= CR hi.
    return rj2 <= lo && (!std::isfinite(X) || i1e - X >= p.cap_ratio * std::max(0.0, hi));
  }

  /// Size of the yield surface against which a trial-stress increment is measured for substepping.
  /// Half its extent along the hydrostat, or where that is unbounded, the larger of |PEAKI1| and
  /// twice the shear strength at the current I1 (von Mises: twice sqrt(J2) at yield).
  static double surface_size(const Params& p, double X, double i1e) {
    const double hi = p.limit.peak_i1;
    double L;
    if (std::isfinite(hi) && std::isfinite(X))
      L = 0.5 * (hi - X);
    else if (std::isfinite(hi))
      L = std::max(std::abs(hi), 2.0 * p.limit.value(std::min(i1e, hi)));
    else
      L = 2.0 * p.limit.a1;
    return std::max(L, 1e-9 * p.B0);
  }

  /// Cap position at evp (-inf without a cap).
  static double cap_at(const Params& p, double evp) {
    return p.crush.active() ? p.crush.cap(evp) : -std::numeric_limits<double>::infinity();
  }
  /// cap_at(p, evp) of a state st (st[1] = evp), to the bit, without its pow or log where the
  /// state holds it: update() writes cap_i1 = crush.cap(evp) whenever evp changes, and its initial
  /// value is P0 = crush.cap(0). Full crush's marker (-DBL_MAX) is not the cap: computed then.
  static double cap_of_state(const Params& p, const double* st) {
    if (p.slot_cap >= 0 && st[p.slot_cap] > -std::numeric_limits<double>::max()) return st[p.slot_cap];
    return cap_at(p, st[1]);
  }

  struct Substep {
    Mat3 dep;            ///< plastic strain increment
    double work = 0.0;   ///< effective stress : plastic strain increment, J/m^3
    double d_eqps = 0.0;
    double pf = -1.0;    ///< pore pressure at the updated evp (plastic substeps; a guess for later solves)
    /// cap_at(p, cap_evp) when the return evaluated it (NaN otherwise): the cap at the updated evp,
    /// if cap_evp is that evp, so that the next substep and the stored state need not recompute it.
    double cap_evp = std::numeric_limits<double>::quiet_NaN();
    double cap_X = std::numeric_limits<double>::quiet_NaN();
  };

  /// Plastic volumetric strain increment of the non-hardening return from trial (I1_t, s_t) onto
  /// the surface at evp; fills the returned point.
  /// `pf_out` comes in as a guess from an earlier solve (e.g. of the same trial), which speeds up
  /// the pore-pressure Newton solve; `hint` carries the warm starts of the previous return of the
  /// same trial (geomodel_return.hpp) and is updated.
  static double return_at(const Params& p, double evp, double c, double K, double I1_t, double rj2_t, GeoPoint& out,
                          double& pf_out, GeoReturnHint& hint) {
    pf_out = pore_pressure(p, evp, pf_out);  // in: a guess (the caller's latest value)
    const double i1e_t = I1_t + 3.0 * pf_out;
    const GeoSurface s = surface(p, evp, hint.kappa);
    hint.kappa = s.kappa;
    if (!(s.f(i1e_t, rj2_t) > 0.0)) {
      out = {i1e_t, rj2_t};
      return 0.0;
    }
    out = geo_closest_point(s, c, i1e_t, rj2_t, nullptr, &hint);
    const double I1_new = out.i1 - 3.0 * pf_out;
    return (I1_t - I1_new) / (3.0 * K);
  }

  /// One substep of inviscid elastic-plastic update from sigma (total stress) with strain increment
  /// deps. Returns false for an elastic substep.
  /// `pf_n`, `X_n`: the pore pressure and the cap position at the start of the substep (computed if
  /// negative, NaN: the caller of a single substep knows them). The moduli are
  /// taken at the midpoint of the elastic trial (explicit midpoint rule: second order in the
  /// step for the pressure-dependent bulk modulus, against first order at the start point).
  static bool substep(const Params& p, Mat3& sigma, double& evp, const Mat3& deps, Substep& out,
                      double pf_n = -1.0, double X_n = std::numeric_limits<double>::quiet_NaN()) {
    if (pf_n < 0.0) pf_n = pore_pressure(p, evp);
    if (std::isnan(X_n)) X_n = cap_at(p, evp);
    const double tr_e = trace(deps);
    double K, G;
    const double i1e_n = trace(sigma) + 3.0 * pf_n;
    moduli(p, i1e_n, evp, K, G);
    if (p.B1 > 0.0) moduli(p, i1e_n + 1.5 * K * tr_e, evp, K, G);
    Mat3 sig_t = sigma + (2.0 * G) * deps;
    const double iso = (K - 2.0 * G / 3.0) * tr_e;
    sig_t(0, 0) += iso;
    sig_t(1, 1) += iso;
    sig_t(2, 2) += iso;
    const double I1_t = trace(sig_t);
    Mat3 s_t = deviator(sig_t);
    double rj2_t = std::sqrt(0.5 * ddot(s_t, s_t));
    // A deviator at the round-off level of the stress (1e-13 of |I1|: a hydrostatic path) is taken
    // as zero: its direction is noise, and a return to a point near the cap tip would otherwise
    // scale that noise up into a spurious shear stress and a shifted I1.
    if (rj2_t <= 1e-13 * std::abs(I1_t)) {
      rj2_t = 0.0;
      s_t = Mat3{};
    }
    // Ff at the trial, if the yield check evaluates it: the return needs it again (an exponential).
    double ff_t = std::numeric_limits<double>::quiet_NaN();
    if (!(yield_value(p, X_n, I1_t + 3.0 * pf_n, rj2_t, &ff_t) > 0.0) && !std::isnan(I1_t)) {
      sigma = sig_t;
      return false;
    }
    const double c = std::sqrt(1.5 * K * p.beta / G);
    GeoPoint pt;
    double pf = pf_n;  // guess for the pore-pressure solves
    double d;
    if (!piece_return(p, evp, pf_n, c, K, I1_t, rj2_t, pt, pf, d, X_n, &out, ff_t)) {
      GeoReturnHint hint;
      const double d0 = return_at(p, evp, c, K, I1_t, rj2_t, pt, pf, hint);
      // With hardening the surface moves with evp: solve for the consistent increment, and return
      // onto the surface of the final state, so that the stress always lies on the surface of its
      // own internal state (pt, pf are those of that return).
      d = (p.hardening() && d0 != 0.0 && !on_unmoved_limit_surface(p, evp, evp + d0, pt, X_n, &out))
              ? hardening_increment(p, evp, c, K, I1_t, rj2_t, d0, pt, pf, hint)
              : d0;
    }
    const double scale = rj2_t > 0.0 ? pt.rootj2 / rj2_t : 0.0;
    const double mean = (pt.i1 - 3.0 * pf) / 3.0;
    Mat3 sig = scale * s_t;
    const double shift = mean - trace(sig) / 3.0;  // keeps tr(sig) = 3 mean whatever the rounding of s_t
    sig(0, 0) += shift;
    sig(1, 1) += shift;
    sig(2, 2) += shift;
    // d_eps_p = C^-1 : (sigma_trial - sigma).
    const Mat3 dev_p = ((1.0 - scale) / (2.0 * G)) * s_t;
    out.dep = dev_p;
    const double dv = (I1_t - trace(sig)) / (3.0 * K);
    out.dep(0, 0) += dv / 3.0;
    out.dep(1, 1) += dv / 3.0;
    out.dep(2, 2) += dv / 3.0;
    out.d_eqps = std::sqrt(2.0 / 3.0 * ddot(dev_p, dev_p));
    Mat3 sig_eff = sig;
    sig_eff(0, 0) += pf;
    sig_eff(1, 1) += pf;
    sig_eff(2, 2) += pf;
    out.work = ddot(sig_eff, out.dep);
    out.pf = pf;
    sigma = sig;
    // The state's evp is the one whose surface holds the stress; it equals evp + dv to the
    // tolerance of the consistency iteration.
    evp += d;
    return true;
  }

  /// True if, drained, the returned point lies on the limit-surface part (I1' > kappa) of both the
  /// surface it was returned to (at evp_old) and the one at the updated strain evp_new: there the
  /// surface does not depend on evp, so the point is also the closest point of the updated surface
  /// (the elastic region is convex and the surface around the point is unchanged: a local closest
  /// point of a convex set is the global one) and the non-hardening increment is consistent.
  /// I1' > kappa exactly when I1' - X > CR Ff(I1') (k - X - CR Ff(k) increases with k and is zero
  /// at kappa), which needs no solve for kappa.
  /// `X_old`, if not NaN, is cap_at(p, evp_old), known to the caller; `cap_new`, if given,
  /// receives cap_at(p, evp_new) when it is evaluated (Substep::cap_evp, cap_X).
  static bool on_unmoved_limit_surface(const Params& p, double evp_old, double evp_new, const GeoPoint& pt,
                                       double X_old = std::numeric_limits<double>::quiet_NaN(),
                                       Substep* cap_new = nullptr) {
    if (p.fluid()) return false;  // the pore pressure moves the whole surface
    const double cr_ff = p.cap_ratio * p.limit.value(pt.i1);
    if (std::isnan(X_old)) X_old = cap_at(p, evp_old);
    if (!(pt.i1 - X_old > cr_ff)) return false;
    const double X_new = cap_at(p, evp_new);
    if (cap_new) {
      cap_new->cap_evp = evp_new;
      cap_new->cap_X = X_new;
    }
    return pt.i1 - X_new > cr_ff;
  }

  /// The coupled-return problem (geomodel_coupled_return.hpp) of a trial at evp.
  static auto coupled_problem(const Params& p, double evp, double c, double K, double I1_t, double rj2_t,
                              double pf_guess) {
    auto pore = [&p](double e, double guess, double& dpf) { return pore_pressure(p, e, guess, &dpf); };
    return GeoCoupledProblem<decltype(pore)>{p.limit, p.cap_ratio, p.crush, pore, evp, c, K, I1_t, rj2_t, pf_guess};
  }

  /// The hardening return solved piece by piece, without the general path's full returns (false,
  /// nothing done, where it does not apply or is not certified). With the pore pressure pf_n of
  /// evp and the effective trial I1' = I1_t + 3 pf_n:
  ///  - a trial outside the cap region (I1' - X >= CR Ff(I1'), i.e. I1' >= kappa, no kappa solve
  ///    needed) is projected onto the limit surface alone. If the point lies outside the cap
  ///    region it is the return: drained, if the cap before and after the increment leaves it
  ///    there (on_unmoved_limit_surface); with a pore fluid, whose pressure moves the trial, after
  ///    Newton on the point and the increment together (geo_limit_coupled_return);
  ///  - a trial under the cap, or whose limit-surface projection lies under it, returns onto the
  ///    cap (the projection lies at an I1 below the trial's, geomodel_projection.hpp): Newton on
  ///    the cap angle and the increment together (geo_cap_coupled_return), from the angle of the
  ///    trial (or of that projection) in the unit-scaled ellipse.
  /// `X_n`, if not NaN, is the cap at evp (the caller's); `cap_new` as on_unmoved_limit_surface's;
  /// `ff_t`, if not NaN, is Ff at the effective trial I1_t + 3 pf_n (the yield check's).
  static bool piece_return(const Params& p, double evp, double pf_n, double c, double K, double I1_t, double rj2_t,
                           GeoPoint& pt, double& pf, double& d,
                           double X_n = std::numeric_limits<double>::quiet_NaN(), Substep* cap_new = nullptr,
                           double ff_t = std::numeric_limits<double>::quiet_NaN()) {
    if (!p.hardening() || !p.crush.active() || !(rj2_t > 0.0)) return false;
    const double X = std::isnan(X_n) ? p.crush.cap(evp) : X_n;
    if (!std::isfinite(X)) return false;
    const auto P = coupled_problem(p, evp, c, K, I1_t, rj2_t, pf_n);
    auto tol = [&](double di) { return increment_tol(di, evp); };
    GeoCoupledResult r;
    const double i1e_t = I1_t + 3.0 * pf_n;
    double i1_start = i1e_t;
    if (std::isnan(ff_t)) ff_t = p.limit.value(i1e_t);
    if (i1e_t - X >= p.cap_ratio * ff_t) {
      GeoPoint q;
      const double z_tol = geo_projection_tol(p.limit, c, i1e_t, rj2_t);
      if (!geo_project_on_limit(p.limit, c, i1e_t, rj2_t, z_tol, q, ff_t)) return false;
      if (q.i1 - X >= p.cap_ratio * q.rootj2) {  // outside the cap region (rootj2 = Ff there)
        if (!p.fluid()) {
          const double d0 = (I1_t - q.i1) / (3.0 * K);
          if (!on_unmoved_limit_surface(p, evp, evp + d0, q, X, cap_new)) return false;
          pt = q;
          pf = 0.0;
          d = d0;
          return true;
        }
        if (!geo_limit_coupled_return(P, q.i1 / std::sqrt(3.0), z_tol, tol, r)) return false;
        pt = r.q;
        pf = r.pf;
        d = r.d;
        return true;
      }
      i1_start = q.i1;
    }
    const double kappa = geo_cap_kappa(p.limit, p.cap_ratio, X);
    const double theta0 = std::atan2(rj2_t / p.limit.value(kappa), (kappa - i1_start) / (kappa - X));
    if (!geo_cap_coupled_return(P, theta0, kappa, tol, r)) return false;
    pt = r.q;
    pf = r.pf;
    d = r.d;
    return true;
  }

  /// Tolerance on the plastic volumetric strain increment: 1e-10 of it, but not below
  /// 1e-14 (1 + |evp|), the noise floor of the return (closest point to ~1e-13 of the stress,
  /// divided by K).
  static double increment_tol(double d0, double evp) {
    return std::max(1e-10 * std::abs(d0), 1e-14 * (1.0 + std::abs(evp)));
  }

  /// The consistent increment of a return whose surface moves with evp, and its returned point:
  /// on the cap by Newton on the cap angle and the increment together
  /// (geomodel_coupled_return.hpp), otherwise, or if that is not certified, by the consistency
  /// iteration around full returns.
  static double hardening_increment(const Params& p, double evp, double c, double K, double I1_t, double rj2_t,
                                    double d0, GeoPoint& pt, double& pf, GeoReturnHint& hint) {
    if (hint.on_cap) {
      GeoCoupledResult r;
      if (geo_cap_coupled_return(coupled_problem(p, evp, c, K, I1_t, rj2_t, pf), hint.theta, hint.kappa,
                                 [&](double) { return increment_tol(d0, evp); }, r)) {
        pt = r.q;
        pf = r.pf;
        return r.d;
      }
    }
    return consistent_increment(p, evp, c, K, I1_t, rj2_t, d0, pt, pf, hint);
  }

  /// Consistency bisection (Homel et al. 2015 §5): the plastic volumetric strain increment d with
  /// d = (increment of the non-hardening return onto the surface at evp + d). phi(d) = inc(d) - d is
  /// decreasing for a hardening cap and for pore pressure, so [d0, 0] brackets the root. If the
  /// surface softens (a retracting cap overtaking the stress) the bracket is widened; if no root is
  /// found, d0 is kept. The iteration runs in u = ln(P3 + evp) where the crush curve is
  /// logarithmic (X = P0 + (u - ln P3)/P1 in compaction), so that it stays well conditioned up to
  /// full crush (evp -> -P3), and otherwise in evp itself; the secant method kept in the bracket
  /// (core/illinois.hpp), at most 80 steps.
  /// Fills (pt, pf) with the return onto the surface of the returned increment.
  static double consistent_increment(const Params& p, double evp, double c, double K, double I1_t, double rj2_t,
                                     double d0, GeoPoint& pt, double& pf, GeoReturnHint& hint) {
    const bool logv = p.crush.active() && d0 < 0.0;
    const double P3 = p.crush.p3;
    // Map between the increment d and the iteration variable x.
    auto to_d = [&](double x) { return logv ? std::exp(x) - P3 - evp : x; };
    auto to_x = [&](double d) { return logv ? std::log(std::max(P3 + evp + d, 1e-300)) : d; };
    auto phi = [&](double x, GeoPoint& q, double& pfq) {
      const double d = to_d(x);
      return return_at(p, evp + d, c, K, I1_t, rj2_t, q, pfq, hint) - d;
    };
    double a = to_x(0.0), fa = d0;  // phi(0) = d0
    double b = to_x(d0);
    GeoPoint q;
    double pfq = pf;  // in: the pore-pressure guess (that of the non-hardening return)
    double fb = phi(b, q, pfq);
    for (int grow = 0; grow < 30 && (fa > 0.0) == (fb > 0.0) && fb != 0.0; ++grow) {
      a = b;
      fa = fb;
      b = to_x(2.0 * to_d(b));
      fb = phi(b, q, pfq);
    }
    if ((fa > 0.0) == (fb > 0.0) && fb != 0.0) {
      const double d = d0;  // no root: the explicit increment
      return_at(p, evp + d, c, K, I1_t, rj2_t, pt, pf, hint);
      return d;
    }
    // Tolerance (increment_tol): the state stays on its own surface regardless (the returned point
    // is the last evaluated one, whose return is kept).
    const double tol = increment_tol(d0, evp);
    GeoPoint qx = q;
    double pfx = pfq;
    auto phi_keep = [&](double x) { return phi(x, qx, pfx); };
    // xtol in x: for the log variable, dx = dd / (P3 + evp + d) >= dd.
    const double x = bracketed_secant_root(phi_keep, a, fa, b, fb, tol, tol, 80);
    pt = qx;
    pf = pfx;
    return to_d(x);
  }

  /// The kinematics kLanes points at a time (material_lanes.hpp), this kernel lane by lane.
  static bool lanes_apply(const Params&) { return true; }
  /// The elastic steps kLanes points at a time (geomodel_elastic_lanes.hpp): where this parameter
  /// set allows it, update_lanes_elastic takes the points of `want` that are certainly elastic at
  /// every substep, updates their stress, state, result (res[l]) and plastic work exactly as
  /// update() would, and returns them.
  static bool elastic_lanes_apply(const Params& p);
  static LaneMask update_lanes_elastic(const Params& p, const LaneKinematics& k, LaneMask want, Mat3L& sigma,
                                       Lane* st, PointResult* res, Lane& plastic_work);

  static void update(const Params& p, const PointKinematics& k, Mat3& sigma, double* st, PointResult& res) {
    const Mat3 eps = k.dt * k.D_bar;
    const Mat3 sigma_n = sigma;
    double eqps = st[0], evp = st[1];
    const double evp_n = evp;
    // The pore pressure of the state (stored with a fluid: the value pore_pressure(evp) written at
    // the end of the previous step, which saves its Newton solve on every elastic step).
    const double pf_n = p.slot_pore_pressure >= 0 ? st[p.slot_pore_pressure] : 0.0;
    const double i1e = trace(sigma) + 3.0 * pf_n;
    // Substep count from the trial-stress increment against the surface size and the change of
    // the bulk modulus over the step.
    double K, G;
    moduli(p, i1e, evp, K, G);
    const double tr_e = trace(eps);
    const double dsig = std::sqrt(9.0 * K * K * tr_e * tr_e / 3.0 + 4.0 * G * G * ddot(deviator(eps), deviator(eps)));
    const double X_n = cap_of_state(p, st);
    double n_need = std::ceil(dsig / surface_size(p, X_n, i1e));
    if (p.B1 > 0.0) {
      double K2, G2;
      moduli(p, i1e + 3.0 * K * tr_e, evp, K2, G2);
      n_need = std::max(n_need, std::ceil(4.0 * std::abs(K2 - K) / K));  // K changes < 25 % per substep
    }
    const int n = std::isfinite(n_need) ? static_cast<int>(std::clamp(n_need, 1.0, double(p.max_substeps)))
                                        : p.max_substeps;
    const Mat3 deps = (1.0 / n) * eps;
    // Duvaut-Lions weight of the inviscid solution per substep (1: rate independent).
    double w = 1.0;
    if (p.T1 > 0.0) {
      const double rate = std::sqrt(2.0 / 3.0 * ddot(k.D_bar, k.D_bar));
      const double tau = p.T2 == 0.0 ? p.T1 : p.T1 * std::pow(rate, -p.T2);
      const double r = (k.dt / n) / tau;
      w = std::isfinite(tau) ? r / (1.0 + r) : 0.0;
    }
    Mat3 dep_sum{};
    double work = 0.0, d_eqps = 0.0;
    double pf_last = pf_n;  // the latest pore pressure known: a start for the final solve
    // The cap at the current evp while it is known (NaN: substep() computes it): each cap costs a
    // pow or a log, and a point at the tensile vertex returns at every step.
    double X_cur = X_n;
    for (int i = 0; i < n; ++i) {
      Substep sub;
      if (w == 1.0) {
        const bool plastic = substep(p, sigma, evp, deps, sub, n == 1 ? pf_n : -1.0, X_cur);
        if (plastic) {
          X_cur = sub.cap_evp == evp ? sub.cap_X : std::numeric_limits<double>::quiet_NaN();
          pf_last = sub.pf;
          dep_sum += sub.dep;
          work += sub.work;
          d_eqps += sub.d_eqps;
        }
        continue;
      }
      // Rate dependent: blend the elastic trial and the inviscid update (Simo & Hughes §2.7.3).
      const Mat3 sig0 = sigma;
      const double evp0 = evp;
      X_cur = std::numeric_limits<double>::quiet_NaN();
      Mat3 sig_inv = sigma;
      if (!substep(p, sig_inv, evp, deps, sub)) {
        sigma = sig_inv;
        continue;
      }
      Mat3 sig_t = sig0;
      elastic_trial(p, sig_t, evp0, deps);
      sigma = (1.0 - w) * sig_t + w * sig_inv;
      evp = evp0 + w * (evp - evp0);
      dep_sum += w * sub.dep;
      work += w * sub.work;
      d_eqps += w * sub.d_eqps;
    }
    eqps += d_eqps;
    st[0] = eqps;
    st[1] = evp;
    st[2] = n;
    // The state's functions of evp, recomputed only if evp moved (an elastic step keeps the values
    // written when evp was last changed, and the initial ones are those of evp = 0).
    if (evp != evp_n) {
      if (p.slot_porosity >= 0) {
        st[p.slot_porosity] = p.crush.porosity(evp);
        // After full crush there is no cap (X = -inf); the field keeps a finite marker, -DBL_MAX.
        // (X_cur, when known, is the cap at this evp: cap_at is crush.cap with a crush curve.)
        const double X = std::isnan(X_cur) ? p.crush.cap(evp) : X_cur;
        st[p.slot_cap] = std::max(X, -std::numeric_limits<double>::max());
      }
      if (p.slot_pore_pressure >= 0) st[p.slot_pore_pressure] = pore_pressure(p, evp, pf_last);
    }
    res.eqps = eqps;
    res.delta_eqps = d_eqps;
    res.plastic_work_density = work;
    res.drucker_product = ddot(sigma - sigma_n, dep_sum);
  }

  /// Elastic trial of one substep, with the moduli taken as in substep().
  static void elastic_trial(const Params& p, Mat3& sigma, double evp, const Mat3& deps) {
    const double pf = pore_pressure(p, evp);
    double K, G;
    moduli(p, trace(sigma) + 3.0 * pf, evp, K, G);
    if (p.B1 > 0.0) moduli(p, trace(sigma) + 3.0 * pf + 1.5 * K * trace(deps), evp, K, G);  // as substep()
    sigma += (2.0 * G) * deps;
    const double iso = (K - 2.0 * G / 3.0) * trace(deps);
    sigma(0, 0) += iso;
    sigma(1, 1) += iso;
    sigma(2, 2) += iso;
  }

  /// wave_speed reads eqps and evp only (MaterialAdapter fetches no other state for it).
  static int wave_speed_state_count(const Params&) { return 2; }

  /// Dilatational wave speed with the stiffest moduli the state allows: K = B0 + B1 (saturated by
  /// Biot-Gassmann at the current porosity with a pore fluid), G at its largest.
  static double wave_speed(const Params& p, const double* state, double J) {
    const double evp = state[1];
    const double Kd = p.B0 + p.B1;
    const double K = p.fluid() ? biot_gassmann(Kd, p.Km, p.Kf, p.crush.porosity(evp)) : Kd;
    double G = p.G0;
    if (p.poisson) G = std::max(1.5 * p.B0 * (1 - 2 * p.nu_low) / (1 + p.nu_low),
                                1.5 * Kd * (1 - 2 * (p.nu_low + p.nu_gain)) / (1 + p.nu_low + p.nu_gain));
    return std::sqrt((K + 4.0 * G / 3.0) * J / p.density);
  }
};

}  // namespace ballista

#include "materials/geomodel_elastic_lanes.hpp"
