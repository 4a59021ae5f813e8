#pragma once
// A test-only pressure-dependent model for the A3-A5 suite tests: hypoelastic, linear
// Drucker-Prager cone with non-associative flow (beta), closed-form return (exact on the flat
// cone), and a crush-curve cap that acts on the hydrostat only (enough for A4/A5, which never
// leave it). Variants: 0 correct; 1 ignores GeoReduction::flow_beta (associative flow: A3 must
// fail); 2 uses a crush curve with P1 doubled (A4/A5 must fail); 3 updates the cap explicitly
// (the stress returns to the start-of-step cap X(evp_n): a one-step lag, first order, which A4/A5
// must notice). Not registered; the state fields follow the geomodel contract
// (notes4/geomodel_spec.md).
#include <cmath>

#include "materials/material_adapter.hpp"
#include "verify/hydrostatic_crush.hpp"

namespace ballista::test {

struct TestGeoHydro {
  static constexpr const char* kName = "test_geo_hydro";
  struct Params {
    double density, bulk, shear, peak_i1, fslope, beta, p0, p1, p3, fixed;
    int variant;
  };
  static std::vector<ParamSpec> param_specs() {
    std::vector<ParamSpec> s;
    for (const char* n : {"density", "bulk_modulus", "shear_modulus", "peak_i1", "fslope", "flow_beta", "crush_p0",
                          "crush_p1", "crush_p3", "fixed_cap", "variant"})
      s.push_back({n, "-", "test parameter"});
    return s;
  }
  static Params make(const ParamValues& v) {
    return {v.at("density"),  v.at("bulk_modulus"), v.at("shear_modulus"), v.at("peak_i1"),
            v.at("fslope"),   v.at("flow_beta"),    v.at("crush_p0"),      v.at("crush_p1"),
            v.at("crush_p3"), v.at("fixed_cap"),    static_cast<int>(v.at("variant"))};
  }
  static ParamValues with_variant(const GeoReduction& g, int variant) {
    return {{"density", g.density}, {"bulk_modulus", g.bulk}, {"shear_modulus", g.shear}, {"peak_i1", g.peak_i1},
            {"fslope", g.fslope},   {"flow_beta", g.flow_beta},       {"crush_p0", g.p0},         {"crush_p1", g.p1},
            {"crush_p3", g.p3},     {"fixed_cap", g.fixed_cap ? 1.0 : 0.0}, {"variant", static_cast<double>(variant)}};
  }
  static ParamValues reduce_to_geo(const GeoReduction& g) { return with_variant(g, 0); }
  static std::vector<StateFieldSpec> state_fields() {
    return {{"plastic_volumetric_strain", "1", 0.0}, {"porosity", "1", 0.0}, {"pore_pressure", "Pa", 0.0}};
  }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* st, PointResult&) {
    const double G = p.shear, K = p.bulk, FS = p.fslope, beta = p.variant == 1 ? 1.0 : p.beta;
    s += k.dt * (2.0 * G) * k.D_bar;
    const double iso = k.dt * (K - 2.0 * G / 3.0) * trace(k.D_bar);
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
    double i1 = trace(s);
    Mat3 d = deviator(s);
    const double rj = std::sqrt(0.5 * ddot(d, d));
    const double f = rj - FS * (p.peak_i1 - i1);
    if (f > 0.0) {
      const double lam = f / (G + 9.0 * K * beta * FS * FS);
      if (rj - lam * G >= 0.0) {
        d = ((rj - lam * G) / rj) * d;
        i1 -= 9.0 * K * beta * FS * lam;
        st[0] += 3.0 * beta * FS * lam;
      } else {  // vertex (hydrostatic tension in A5)
        st[0] += (i1 - p.peak_i1) / (3.0 * K);
        d = Mat3();
        i1 = p.peak_i1;
      }
    }
    if (p.p3 > 0.0) {
      const CrushCurve c{p.p0, p.variant == 2 ? 2.0 * p.p1 : p.p1, p.p3};
      const double x = p.fixed > 0.0 ? p.p0 : c.cap(st[0]);
      if (i1 < x) {
        const double ev = st[0] + i1 / (3.0 * K);  // total volumetric strain (constant K)
        if (p.variant == 3 && p.fixed <= 0.0) {
          st[0] = ev - x / (3.0 * K);  // stress to the old cap, all excess strain plastic
          i1 = x;
        } else {
          st[0] = p.fixed > 0.0 ? ev - p.p0 / (3.0 * K) : solve_compaction(c, K, ev, st[0]);
          i1 = p.fixed > 0.0 ? p.p0 : c.cap(st[0]);
        }
      }
      st[1] = -std::expm1(-(p.p3 + st[0]));
    }
    s = d + Mat3::diag(i1 / 3.0, i1 / 3.0, i1 / 3.0);
  }
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

}  // namespace ballista::test
