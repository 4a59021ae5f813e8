#pragma once
// Test helper: drives points of one material through prescribed deformation-gradient paths using
// the real registry, MaterialAdapter and FieldStore, the way a solver does. The velocity gradient
// over a step is L = (F_{n+1} F_n^{-1} - I)/dt (thesis seed 000, eq. 4.10; CATALOGUE §A).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <memory>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "materials/material.hpp"

namespace ballista::test {

/// Runs the enclosing scope on one thread (single-point paths of 10^5-10^6 steps: a parallel
/// region per step costs far more than the point update on a loaded machine).
class SerialGuard {
 public:
  SerialGuard() : saved_(max_threads()) { set_threads(1); }
  ~SerialGuard() { set_threads(saved_); }
  SerialGuard(const SerialGuard&) = delete;
  SerialGuard& operator=(const SerialGuard&) = delete;

 private:
  int saved_;
};

inline ParamValues elastic_kg(double rho, double K, double G) {
  return {{"density", rho}, {"bulk_modulus", K}, {"shear_modulus", G}};
}

/// A J2 steel with linear hardening (the adapter's tests): sigma_y = 300 MPa, H = 1 GPa.
inline ParamValues j2_steel_values() {
  ParamValues v = elastic_kg(7800, 160e9, 80e9);
  v["yield_stress"] = 300e6;
  v["hardening_modulus"] = 1e9;
  return v;
}

inline std::unique_ptr<Material> make_material(const std::string& model, const ParamValues& v) {
  const MaterialFactory* f = find_material(model);
  if (!f) {
    ADD_FAILURE() << "model '" << model << "' is not registered";
    return nullptr;
  }
  return f->create("test_" + model, v);
}

class PointDriver {
 public:
  /// Batches of fewer than 1000 points run on one thread while the driver lives (see SerialGuard).
  PointDriver(const std::string& model, const ParamValues& v, Index n = 1) : mat_(make_material(model, v)) {
    if (n < 1000) serial_.emplace();
    store_.add_real("F_old", 9, "1");
    store_.add_real("F", 9, "1");
    store_.add_real("L", 9, "1/s");
    store_.add_real("R", 9, "1");
    store_.add_real("stress", 9, "Pa");
    store_.add_real("plastic_work", 1, "J/m^3");
    if (mat_) mat_->declare_fields(store_);
    store_.resize(n);
    for (Index p = 0; p < n; ++p) {
      F(p) = Mat3::identity();
      store_.view<Mat3>("F_old")[p] = Mat3::identity();
      R(p) = Mat3::identity();
    }
    all_.resize(static_cast<size_t>(n));
    std::iota(all_.begin(), all_.end(), Index{0});
  }

  Material& material() { return *mat_; }
  FieldStore& store() { return store_; }
  Mat3& F(Index p = 0) { return store_.view<Mat3>("F")[p]; }
  Mat3& R(Index p = 0) { return store_.view<Mat3>("R")[p]; }
  Mat3& stress(Index p = 0) { return store_.view<Mat3>("stress")[p]; }
  double& plastic_work(Index p = 0) { return store_.real("plastic_work")[p]; }
  double& state(const std::string& name, Index p = 0) { return store_.real(name)[p]; }
  /// Unrotated stress R^T sigma R of point p.
  Mat3 stress_bar(Index p = 0) { return unrotate(R(p), stress(p)); }

  /// Sets F_new of point p (call for every point of the batch, then step()).
  void set_F(Index p, const Mat3& F_new) {
    store_.view<Mat3>("F_old")[p] = F(p);
    F(p) = F_new;
    store_.view<Mat3>("L")[p] = (1.0 / dt_) * (F_new * inverse(store_.view<Mat3>("F_old")[p]) - Mat3::identity());
  }

  /// Advances the given points (all if empty) by dt after set_F.
  void step(double dt, const std::vector<Index>& points = {}) {
    const std::vector<Index>& idx = points.empty() ? all_ : points;
    MaterialBatch b;
    b.points = idx.data();
    b.count = static_cast<Index>(idx.size());
    b.F_old = store_.view<Mat3>("F_old");
    b.F_new = store_.view<Mat3>("F");
    b.L = store_.view<Mat3>("L");
    b.R = store_.view<Mat3>("R");
    b.stress = store_.view<Mat3>("stress");
    b.plastic_work = store_.real("plastic_work");
    b.store = &store_;
    b.dt = dt;
    b.distortion_limit = distortion_limit_;
    b.distortion_remaps = &remaps_;
    mat_->update(b);
  }
  /// MaterialBatch::distortion_limit of the following steps (0: never remap).
  void set_distortion_limit(double limit) { distortion_limit_ = limit; }
  Index distortion_remaps() const { return remaps_.load(); }

  /// One step of point 0 to F_new over dt.
  void advance(const Mat3& F_new, double dt) {
    dt_ = dt;
    set_F(0, F_new);
    step(dt, {0});
  }
  void set_dt(double dt) { dt_ = dt; }

 private:
  std::optional<SerialGuard> serial_;
  std::unique_ptr<Material> mat_;
  FieldStore store_;
  std::vector<Index> all_;
  double dt_ = 1.0;
  double distortion_limit_ = 0.0;
  std::atomic<Index> remaps_{0};
};

/// CATALOGUE A6 objectivity paths: n pairs of points of `d` (which must hold 2n points) follow
/// F_k(t) = I + t A_k, t = s/N, A_k entries uniform in +-amplitude. Point 2k is unrotated; point
/// 2k+1 carries a superimposed rotation Q: constant (a random angle about a random axis, also its
/// starting F and R) or, if `time_dependent`, 3 pi t about a random axis with L rotated as Q L_k.
/// `after_step(s)` runs after every step. Draws from `rng` in a fixed order (A, axis, angle).
inline void drive_rotated_pairs(PointDriver& d, int n, int N, double amplitude, double dt, bool time_dependent,
                                std::mt19937& rng, std::uniform_real_distribution<double>& u,
                                const std::function<void(int)>& after_step) {
  std::vector<Mat3> A(n), Q0(n);
  std::vector<Vec3> axis(n);
  for (int k = 0; k < n; ++k) {
    for (double& a : A[k].a) a = amplitude * u(rng);
    axis[k] = Vec3{{u(rng), u(rng), u(rng)}};
    axis[k] = (1.0 / norm(axis[k])) * axis[k];
    Q0[k] = rotation_about(axis[k], 3.0 * u(rng));
    if (!time_dependent) {
      d.F(2 * k + 1) = Q0[k];
      d.R(2 * k + 1) = Q0[k];
    }
  }
  d.set_dt(dt);
  for (int s = 1; s <= N; ++s) {
    const double t = double(s) / N;
    for (int k = 0; k < n; ++k) {
      const Mat3 F = Mat3::identity() + t * A[k];
      const Mat3 Q = time_dependent ? rotation_about(axis[k], 3.0 * std::numbers::pi * t) : Q0[k];
      d.set_F(2 * k, F);
      d.set_F(2 * k + 1, Q * F);
      if (time_dependent) d.store().view<Mat3>("L")[2 * k + 1] = rotate(Q, d.store().view<Mat3>("L")[2 * k]);
    }
    d.step(dt);
    after_step(s);
  }
}

/// Piecewise-linear interpolation of a table (t_k, y_k) at t (t within the table).
inline double interp(const std::vector<double>& t, const std::vector<double>& y, double x) {
  for (size_t k = 1; k < t.size(); ++k)
    if (x <= t[k]) return y[k - 1] + (y[k] - y[k - 1]) * (x - t[k - 1]) / (t[k] - t[k - 1]);
  return y.back();
}

/// The strain increment the adapter hands a model for a uniaxial step F11: F_prev -> F (stretch
/// lambda = F / F_prev, x = lambda - 1): the midpoint increment 2 (lambda - 1)/(lambda + 1) =
/// x / (1 + x/2) (materials/strain_increment.hpp, Hughes & Winget 1980), evaluated the way the
/// adapter does, so sums of it match the model's to round-off. ln lambda + O(x^3/12).
inline double stretch_increment(double F, double F_prev) {
  const double x = F / F_prev - 1.0;
  return x / (1.0 + 0.5 * x);
}

inline double rel_diff(const Mat3& A, const Mat3& B) {
  const double scale = std::max(frobenius(A), frobenius(B));
  return scale > 0 ? frobenius(A - B) / scale : 0.0;
}

}  // namespace ballista::test
