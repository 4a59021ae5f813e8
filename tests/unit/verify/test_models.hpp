#pragma once
// Test-only material models for the verification suite's own tests: they let the tests show that
// each check passes a correct model and fails a wrong one. They are not registered (the suite
// functions take a MaterialFactory, built here by test_factory).
#include <cmath>
#include <memory>

#include "materials/material_adapter.hpp"

namespace ballista::test {

/// A MaterialFactory for Model with its verification hooks, as BALLISTA_REGISTER_MATERIAL makes one.
template <class Model>
MaterialFactory test_factory() {
  MaterialFactory f;
  f.model = Model::kName;
  f.description = "test model";
  f.params = Model::param_specs();
  f.state_fields = Model::state_fields();
  f.create = [](const std::string& name, const ParamValues& v) -> std::unique_ptr<Material> {
    return std::make_unique<MaterialAdapter<Model>>(name, Model::make(v));
  };
  f.example = verification_example<Model>();
  f.reduce_elastic = verification_reduce_elastic<Model>();
  f.reduce_j2 = verification_reduce_j2<Model>();
  return f;
}

inline std::vector<ParamSpec> test_specs(std::initializer_list<const char*> names) {
  std::vector<ParamSpec> s;
  for (const char* n : names) s.push_back({n, "-", "test parameter"});
  return s;
}

/// J2 plasticity (hypoelastic predictor, radial return, linear isotropic hardening) that fills
/// the algorithmic tangent of Simo & Hughes, Computational Inelasticity (1998), Box 3.2:
///   C = K 1(x)1 + 2G theta I_dev - 2G theta_bar n(x)n,  theta = 1 - 2G dgamma/|s_trial|,
///   theta_bar = 1/(1 + H/3G) - (1 - theta)
/// (variant 0). Variant 1 fills the continuum tangent instead (theta = 1, theta_bar = 1/(1+H/3G)),
/// which is not the derivative of the discrete update; variant 2 the consistent one with
/// engineering shear strains (shear columns halved), a convention error.
struct TangentJ2 {
  static constexpr const char* kName = "test_tangent_j2";
  struct Params {
    double density, bulk, shear, yield, hardening;
    int variant;
  };
  static std::vector<ParamSpec> param_specs() {
    return test_specs({"density", "bulk", "shear", "yield", "hardening", "variant"});
  }
  static Params make(const ParamValues& v) {
    return {v.at("density"), v.at("bulk"), v.at("shear"), v.at("yield"), v.at("hardening"),
            static_cast<int>(v.at("variant"))};
  }
  static ParamValues example_with(int variant) {
    return {{"density", 7800}, {"bulk", 160e9}, {"shear", 80e9}, {"yield", 400e6}, {"hardening", 2e9},
            {"variant", variant}};
  }
  static ParamValues example_params() { return example_with(0); }
  static std::vector<StateFieldSpec> state_fields() { return {{"eqps", "1", 0.0}}; }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* state, PointResult& res) {
    const double G = p.shear, K = p.bulk, H = p.hardening;
    s += k.dt * (2.0 * G) * k.D_bar;
    const double iso = k.dt * (K - 2.0 * G / 3.0) * trace(k.D_bar);
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
    const double mean = trace(s) / 3.0;
    const Mat3 xi = deviator(s);
    const double nx = frobenius(xi), q = std::sqrt(1.5) * nx;
    const double f = q - (p.yield + H * state[0]);
    double theta = 1.0, theta_bar = 0.0;
    Mat3 n;
    if (nx > 0.0) n = (1.0 / nx) * xi;
    if (f > 0.0) {
      const double dep = f / (3.0 * G + H);
      const double scale = 1.0 - 3.0 * G * dep / q;  // = theta
      s = scale * xi + Mat3::diag(mean, mean, mean);
      state[0] += dep;
      theta = p.variant == 1 ? 1.0 : scale;
      theta_bar = 1.0 / (1.0 + H / (3.0 * G)) - (1.0 - theta);
    }
    if (!res.tangent) return;
    static constexpr int I[6] = {0, 1, 2, 1, 0, 0}, J[6] = {0, 1, 2, 2, 2, 1};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        const bool ni = i < 3, nj = j < 3;
        const double n_E = nj ? n(I[j], J[j]) : 2.0 * n(I[j], J[j]);  // n : E_j (tensor shear)
        double c = (ni && nj ? K - 2.0 * G * theta / 3.0 : 0.0) + (i == j ? 2.0 * G * theta : 0.0) -
                   2.0 * G * theta_bar * n(I[i], J[i]) * n_E;
        if (p.variant == 2 && !nj) c *= 0.5;
        res.tangent[6 * i + j] = c;
      }
  }
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

/// J2 plasticity with linear isotropic and linear kinematic (Prager) hardening, radial return on
/// xi = s - alpha (Simo & Hughes 1998, Box 3.1 with kinematic hardening):
///   delta eps_p = (sqrt(3/2)|xi_trial| - sigma_y(eps_p)) / (3G + H_iso + H_kin),
///   s = s_trial - 2G sqrt(3/2) delta eps_p n,  alpha += (2/3) H_kin sqrt(3/2) delta eps_p n.
/// `prager_factor` scales the backstress update (1 = correct, 1.5 = the common slip of dropping 2/3):
/// the A2-kin check must pass the first and fail the second. Nothing in the library has kinematic
/// hardening yet, so this model is what exercises A2-kin before such a model is merged.
struct TestJ2Mixed {
  static constexpr const char* kName = "test_j2_mixed";
  struct Params {
    double density, bulk, shear, yield, h_iso, h_kin, prager_factor;
  };
  static std::vector<ParamSpec> param_specs() {
    return test_specs({"density", "bulk", "shear", "yield", "h_iso", "h_kin", "prager_factor"});
  }
  static Params make(const ParamValues& v) {
    return {v.at("density"), v.at("bulk"), v.at("shear"), v.at("yield"), v.at("h_iso"), v.at("h_kin"),
            v.at("prager_factor")};
  }
  static ParamValues example_params() { return reduce_to_j2(7800, 160e9, 80e9, 400e6, 1e9, 2e9); }
  static ParamValues reduce_to_j2(double rho, double K, double G, double sy, double hi, double hk) {
    return {{"density", rho}, {"bulk", K}, {"shear", G}, {"yield", sy}, {"h_iso", hi}, {"h_kin", hk},
            {"prager_factor", 1.0}};
  }
  static std::vector<StateFieldSpec> state_fields() {
    return {{"eqps", "1", 0.0}, {"a11", "Pa", 0.0}, {"a22", "Pa", 0.0}, {"a33", "Pa", 0.0},
            {"a23", "Pa", 0.0}, {"a13", "Pa", 0.0}, {"a12", "Pa", 0.0}};
  }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double* st, PointResult&) {
    const double G = p.shear;
    s += k.dt * (2.0 * G) * k.D_bar;
    const double iso = k.dt * (p.bulk - 2.0 * G / 3.0) * trace(k.D_bar);
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
    Mat3 alpha;
    alpha(0, 0) = st[1]; alpha(1, 1) = st[2]; alpha(2, 2) = st[3];
    alpha(1, 2) = alpha(2, 1) = st[4]; alpha(0, 2) = alpha(2, 0) = st[5]; alpha(0, 1) = alpha(1, 0) = st[6];
    const Mat3 xi = deviator(s) - alpha;
    const double nx = frobenius(xi), q = std::sqrt(1.5) * nx;
    const double f = q - (p.yield + p.h_iso * st[0]);
    if (!(f > 0.0)) return;
    const double dep = f / (3.0 * G + p.h_iso + p.h_kin);
    const Mat3 n = (1.0 / nx) * xi;
    s += (-2.0 * G * std::sqrt(1.5) * dep) * n;
    alpha += (p.prager_factor * 2.0 / 3.0 * p.h_kin * std::sqrt(1.5) * dep) * n;
    st[0] += dep;
    st[1] = alpha(0, 0); st[2] = alpha(1, 1); st[3] = alpha(2, 2);
    st[4] = alpha(1, 2); st[5] = alpha(0, 2); st[6] = alpha(0, 1);
  }
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

/// Volumetric only, written in J: sigma_bar = K ln(J_{n+1}) I, with the tangent of a spin-free step
/// whose midpoint increment (materials/strain_increment.hpp) is eps: dF = (I - eps/2)^-1 (I + eps/2),
/// J_{n+1} = J_n det(I + eps/2) / det(I - eps/2), so d ln J / d eps = ((I + eps/2)^-1 +
/// (I - eps/2)^-1)/2 (d ln det A = A^-T : dA). A kernel whose response depends on
/// J (every equation of state) has this kind of tangent; the FD check must realise the perturbed
/// steps without spin for it to hold (a6_tangent.cpp).
struct TangentLogVolume {
  static constexpr const char* kName = "test_tangent_log_volume";
  struct Params {
    double density, bulk;
  };
  static std::vector<ParamSpec> param_specs() { return test_specs({"density", "bulk"}); }
  static Params make(const ParamValues& v) { return {v.at("density"), v.at("bulk")}; }
  static ParamValues example_params() { return {{"density", 1000}, {"bulk", 2e9}}; }
  static std::vector<StateFieldSpec> state_fields() { return {}; }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double*, PointResult& res) {
    const double pr = p.bulk * std::log(k.J_new);
    s = Mat3::diag(pr, pr, pr);
    if (!res.tangent) return;
    const Mat3 eps = k.dt * k.D_bar;
    const Mat3 inv = 0.5 * (inverse(Mat3::identity() + 0.5 * eps) + inverse(Mat3::identity() - 0.5 * eps));
    static constexpr int I[6] = {0, 1, 2, 1, 0, 0}, J[6] = {0, 1, 2, 2, 2, 1};
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        res.tangent[6 * i + j] = i < 3 ? p.bulk * (j < 3 ? 1.0 : 2.0) * inv(I[j], J[j]) : 0.0;
  }
  static double wave_speed(const Params& p, const double*, double J) { return std::sqrt(p.bulk * J / p.density); }
};

/// Not objective: sigma_bar = K tr(e) I + 2G dev(e) with e = sym(F - I) of the *spatial* F, so a
/// rigid rotation strains it. Must fail A1 and A6-objectivity.
struct NonObjectiveElastic {
  static constexpr const char* kName = "test_non_objective";
  struct Params {
    double density, bulk, shear;
  };
  static std::vector<ParamSpec> param_specs() { return test_specs({"density", "bulk", "shear"}); }
  static Params make(const ParamValues& v) { return {v.at("density"), v.at("bulk"), v.at("shear")}; }
  static ParamValues example_params() { return {{"density", 1000}, {"bulk", 2e9}, {"shear", 1e9}}; }
  static ParamValues reduce_to_elastic(double rho, double K, double G) {
    return {{"density", rho}, {"bulk", K}, {"shear", G}};
  }
  static std::vector<StateFieldSpec> state_fields() { return {}; }
  static void update(const Params& p, const PointKinematics& k, Mat3& s, double*, PointResult&) {
    const Mat3 e = sym(k.F_new - Mat3::identity());
    s = (2.0 * p.shear) * deviator(e);
    const double iso = p.bulk * trace(e);
    s(0, 0) += iso; s(1, 1) += iso; s(2, 2) += iso;
  }
  static double wave_speed(const Params& p, const double*, double J) {
    return std::sqrt((p.bulk + 4.0 * p.shear / 3.0) * J / p.density);
  }
};

}  // namespace ballista::test
