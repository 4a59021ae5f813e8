#pragma once
// Turns a per-point kernel (see material.hpp) into a Material that updates a batch of points.
#include <algorithm>
#include <string>
#include <vector>

#include "core/polar.hpp"
#include "materials/material.hpp"

namespace ballista {

template <class Model>
class MaterialAdapter final : public Material {
 public:
  MaterialAdapter(std::string name, typename Model::Params params)
      : name_(std::move(name)), params_(params), state_(active_state_fields(params_)) {}

  const std::string& name() const override { return name_; }
  const char* model() const override { return Model::kName; }
  double density() const override { return params_.density; }
  std::vector<StateFieldSpec> state_fields() const override { return state_; }
  const typename Model::Params& params() const { return params_; }

  Mat3 initial_stress(const Mat3& F) const override {
    Mat3 R, U;
    polar_decompose(F, R, U);
    return initial_stress_impl(F, R);
  }

  void update(const MaterialBatch& b) const override {
    constexpr int kMaxState = 16;
    const int ns = static_cast<int>(state_.size());
    std::vector<double*> sptr(ns);
    for (int s = 0; s < ns; ++s) sptr[s] = b.store->real(state_[s].name);
    const Params& prm = params_;
    for_each(0, b.count, [&](Index k) {
      const Index p = b.points[k];
      PointKinematics kin;
      kin.F_new = b.F_new[p];
      const Mat3& L = b.L[p];
      // F_new = (I + dt L) F_old (thesis seed 000 eq. 4.9): when F_old is not stored it is
      // recovered for the models that read it (Model::kNeedsFOld), and J_old = J_new / det(A).
      const Mat3 A = Mat3::identity() + b.dt * L;
      const double detA = det(A);
      if (b.F_old)
        kin.F_old = b.F_old[p];
      else if constexpr (kNeedsFOld)
        kin.F_old = inverse(A) * kin.F_new;
      else
        kin.F_old = Mat3{};  // not read by this model
      kin.dt = b.dt;
      kin.J_new = det(kin.F_new);
      kin.J_old = kin.J_new / detA;
      const Mat3 R_old = b.R[p];
      const Mat3 D = sym(L);
      kin.R_new = polar_rotation(kin.F_new, R_old);
      kin.D_bar = unrotate_sym(kin.R_new, D);
      const Mat3 sigma_old = b.stress[p];
      Mat3 sigma_bar = unrotate_sym(R_old, sigma_old);
      double st[kMaxState];
      for (int s = 0; s < ns; ++s) st[s] = sptr[s][p];
      PointResult res;
      if (b.tangent) res.tangent = b.tangent + 36 * p;
      Model::update(prm, kin, sigma_bar, st, res);
      for (int s = 0; s < ns; ++s) sptr[s][p] = st[s];
      const Mat3 sigma_new = rotate_sym(kin.R_new, sigma_bar);
      b.stress[p] = sigma_new;
      b.R[p] = kin.R_new;
      if (b.plastic_work) b.plastic_work[p] = res.plastic_work_density;
      if (b.internal_energy) {
        const double V_new = b.volume0[p] * kin.J_new;
        const double V_old = b.volume0[p] * kin.J_old;
        b.internal_energy[p] += b.dt * 0.5 * (V_old + V_new) * 0.5 * ddot(sigma_old + sigma_new, D);
        b.plastic_energy[p] += res.plastic_work_density * V_new;
      }
      if (b.first_bad && !all_finite(sigma_new)) {
        Index cur = b.first_bad->load(std::memory_order_relaxed);
        while (p < cur && !b.first_bad->compare_exchange_weak(cur, p, std::memory_order_relaxed)) {
        }
      }
    });
  }

  double max_signal_speed(const FieldStore& store, const Index* points, Index count) const override {
    constexpr int kMaxState = 16;
    const int ns = static_cast<int>(state_.size());
    std::vector<const double*> sptr(ns);
    for (int s = 0; s < ns; ++s) sptr[s] = store.real(state_[s].name);
    const Mat3* F = store.view<Mat3>("F");
    const Vec3* v = store.view<Vec3>("v");
    double vmax = 0.0;
#pragma omp parallel for reduction(max : vmax) schedule(static) if (count > kParallelThreshold)
    for (Index k = 0; k < count; ++k) {
      const Index p = points[k];
      double st[kMaxState];
      for (int s = 0; s < ns; ++s) st[s] = sptr[s][p];
      vmax = std::max(vmax, Model::wave_speed(params_, st, det(F[p])) + norm(v[p]));
    }
    return vmax;
  }

  double wave_speed(const FieldStore& store, Index p, double J) const override {
    constexpr int kMaxState = 16;
    double st[kMaxState];
    for (size_t s = 0; s < state_.size(); ++s) st[s] = store.real(state_[s].name)[p];
    return Model::wave_speed(params_, st, J);
  }

 private:
  using Params = typename Model::Params;
  /// The state fields this instance uses. A model whose state depends on its parameters (J2
  /// without backstress, an EOS without energy) defines `state_fields(const Params&)`, returning a
  /// subset of `state_fields()` (the full list, which the registry shows); the kernel then receives
  /// exactly those fields, in that order.
  static std::vector<StateFieldSpec> active_state_fields(const typename Model::Params& p) {
    if constexpr (requires { Model::state_fields(p); }) return Model::state_fields(p);
    else return Model::state_fields();
  }
  /// Models that read PointKinematics::F_old declare `static constexpr bool kNeedsFOld = true`.
  static constexpr bool kNeedsFOld = [] {
    if constexpr (requires { Model::kNeedsFOld; }) return Model::kNeedsFOld;
    else return false;
  }();
  // Hyperelastic models define initial_stress(params, F); hypoelastic ones start stress-free.
  Mat3 initial_stress_impl(const Mat3& F, const Mat3& R) const {
    if constexpr (requires { Model::initial_stress(params_, F); }) {
      (void)R;
      return Model::initial_stress(params_, F);
    } else {
      (void)F; (void)R;
      return Mat3{};
    }
  }

  std::string name_;
  Params params_;
  std::vector<StateFieldSpec> state_;
};

/// Optional verification hooks of a model (see MaterialFactory); null when the model lacks them.
template <class Model>
constexpr auto verification_example() -> ParamValues (*)() {
  if constexpr (requires { Model::example_params(); }) return &Model::example_params;
  else return nullptr;
}
template <class Model>
constexpr auto verification_reduce_elastic() -> ParamValues (*)(double, double, double) {
  if constexpr (requires { Model::reduce_to_elastic(1.0, 1.0, 1.0); }) return &Model::reduce_to_elastic;
  else return nullptr;
}
template <class Model>
constexpr auto verification_reduce_j2() -> ParamValues (*)(double, double, double, double, double, double) {
  if constexpr (requires { Model::reduce_to_j2(1.0, 1.0, 1.0, 1.0, 1.0, 1.0); }) return &Model::reduce_to_j2;
  else return nullptr;
}

/// Registers Model under Model::kName; use once per model file at namespace scope.
#define BALLISTA_REGISTER_MATERIAL(Model, Description)                                         \
  namespace {                                                                                  \
  const bool registered_##Model = ::ballista::register_material(::ballista::MaterialFactory{   \
      Model::kName, Description, Model::param_specs(), Model::state_fields(),                  \
      [](const std::string& name, const ::ballista::ParamValues& v)                            \
          -> std::unique_ptr<::ballista::Material> {                                           \
        return std::make_unique<::ballista::MaterialAdapter<Model>>(name, Model::make(v));     \
      },                                                                                       \
      ::ballista::verification_example<Model>(), ::ballista::verification_reduce_elastic<Model>(), \
      ::ballista::verification_reduce_j2<Model>()});                                           \
  }
}  // namespace ballista
