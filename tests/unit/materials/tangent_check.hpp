#pragma once
// Finite-difference check of the algorithmic tangent PointResult::tangent (material.hpp:
// d sigma_bar_{n+1} / d eps, eps = D_bar dt, 6x6 row-major, order 11, 22, 33, 23, 13, 12, tensor
// shear strains) for one point stepped through the real adapter from a prescribed state.
//
// The state at t_n is (F_n, R_n = polar(F_n), sigma_bar_n, state fields). A strain increment eps is
// applied as the spin-free step of CATALOGUE A6 (src/verify/a6_tangent.cpp):
//   F_{n+1} = R A R^T F_n,  A = (I - eps/2)^-1 (I + eps/2),  R = polar rotation of F_{n+1} (fixed
// point), so L dt = R (A - I) R^T is symmetric and the adapter's midpoint increment
// (materials/strain_increment.hpp) is D_bar dt = eps exactly; J_{n+1} = J_n det(A).
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "core/polar.hpp"
#include "materials/strain_increment.hpp"
#include "material_driver.hpp"

namespace ballista::test {

inline constexpr int kTanI[6] = {0, 1, 2, 1, 0, 0};
inline constexpr int kTanJ[6] = {0, 1, 2, 2, 2, 1};

/// Symmetric tensor from its six tensor components (11, 22, 33, 23, 13, 12).
inline Mat3 sym6(const double e[6]) {
  Mat3 m;
  for (int c = 0; c < 6; ++c) m(kTanI[c], kTanJ[c]) = m(kTanJ[c], kTanI[c]) = e[c];
  return m;
}

/// A point of `model` in a prescribed state, stepped by a spin-free strain increment.
class TangentPoint {
 public:
  TangentPoint(const std::string& model, const ParamValues& v) : mat_(make_material(model, v)) {
    for (auto name : {"F_old", "F", "L", "R", "stress"}) base_.add_real(name, 9, "1");
    mat_->declare_fields(base_);
    base_.resize(1);
    set_F(Mat3::identity());
  }
  /// F_n (R_n = its polar rotation); call before set_stress_bar.
  void set_F(const Mat3& F_n) {
    F_n_ = F_n;
    R_n_ = polar_rotation(F_n);
    base_.view<Mat3>("F")[0] = F_n;
    base_.view<Mat3>("F_old")[0] = F_n;
    base_.view<Mat3>("R")[0] = R_n_;
  }
  /// Unrotated stress at t_n (stored spatially, R_n sigma_bar R_n^T).
  void set_stress_bar(const Mat3& s) { base_.view<Mat3>("stress")[0] = rotate(R_n_, s); }
  void set_state(const std::string& name, double x) { base_.real(name)[0] = x; }
  /// A state field after the last step().
  double state_after(const std::string& name) const { return last_.real(name)[0]; }

  /// Unrotated stress after one step of increment eps over dt; the tangent (36) if non-null.
  Mat3 step(const Mat3& eps, double dt, double* tangent = nullptr) {
    last_ = base_;
    FieldStore& s = last_;
    const Mat3 A = spin_free_step_for_increment(eps);
    Mat3 R = R_n_;
    for (int it = 0; it < 200; ++it) {  // R = polar(R A R^T F_n); contracts by ~|eps| per pass
      const Mat3 R_next = polar_rotation(rotate(R, A) * F_n_, R);
      const double change = frobenius(R_next - R);
      R = R_next;
      if (change < 1e-15) break;
    }
    const Mat3 F = rotate(R, A) * F_n_;
    s.view<Mat3>("F")[0] = F;
    s.view<Mat3>("L")[0] = (1.0 / dt) * (F * inverse(F_n_) - Mat3::identity());
    const Index idx = 0;
    MaterialBatch b;
    b.points = &idx;
    b.count = 1;
    b.F_old = s.view<Mat3>("F_old");
    b.F_new = s.view<Mat3>("F");
    b.L = s.view<Mat3>("L");
    b.R = s.view<Mat3>("R");
    b.stress = s.view<Mat3>("stress");
    b.store = &s;
    b.dt = dt;
    b.tangent = tangent;
    mat_->update(b);
    return unrotate(s.view<Mat3>("R")[0], s.view<Mat3>("stress")[0]);
  }

 private:
  SerialGuard serial_;
  std::unique_ptr<Material> mat_;
  FieldStore base_, last_;
  Mat3 F_n_, R_n_;
};

struct TangentError {
  double rel_err = 0.0;    ///< max_ij |T_fd - T| / max |T|
  double max_entry = 0.0;  ///< max |T|, Pa
  double T[36]{};          ///< the model's tangent
};

/// Central differences with step h on each tensor component of eps0 (a shear column perturbs
/// eps_ab and eps_ba together, the tensor-shear convention of the tangent).
inline TangentError fd_tangent_error(TangentPoint& pt, const Mat3& eps0, double dt, double h) {
  TangentError out;
  for (double& t : out.T) t = std::nan("");
  pt.step(eps0, dt, out.T);
  for (double t : out.T) out.max_entry = std::max(out.max_entry, std::abs(t));
  double err = 0.0;
  for (int j = 0; j < 6; ++j) {
    Mat3 E;
    E(kTanI[j], kTanJ[j]) = 1.0;
    E(kTanJ[j], kTanI[j]) = 1.0;
    const Mat3 sp = pt.step(eps0 + h * E, dt), sm = pt.step(eps0 + (-h) * E, dt);
    for (int i = 0; i < 6; ++i) {
      const double fd = (sp(kTanI[i], kTanJ[i]) - sm(kTanI[i], kTanJ[i])) / (2.0 * h);
      const double d = std::abs(fd - out.T[6 * i + j]);
      err = std::isnan(d) ? std::numeric_limits<double>::infinity() : std::max(err, d);
    }
  }
  out.rel_err = err / out.max_entry;
  return out;
}

}  // namespace ballista::test
