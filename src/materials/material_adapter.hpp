#pragma once
// Turns a per-point kernel (see material.hpp) into a Material that updates a batch of points.
#include <string>
#include <vector>

#include "core/polar.hpp"
#include "materials/material.hpp"

namespace ballista {

template <class Model>
class MaterialAdapter final : public Material {
 public:
  MaterialAdapter(std::string name, typename Model::Params params)
      : name_(std::move(name)), params_(params), state_(Model::state_fields()) {}

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
      kin.F_old = b.F_old[p];
      kin.F_new = b.F_new[p];
      kin.dt = b.dt;
      const Mat3 R_old = b.R[p];
      kin.R_new = polar_rotation(kin.F_new, R_old);
      kin.D_bar = unrotate(kin.R_new, sym(b.L[p]));
      Mat3 sigma_bar = unrotate(R_old, b.stress[p]);
      double st[kMaxState];
      for (int s = 0; s < ns; ++s) st[s] = sptr[s][p];
      PointResult res;
      Model::update(prm, kin, sigma_bar, st, res);
      for (int s = 0; s < ns; ++s) sptr[s][p] = st[s];
      b.stress[p] = rotate(kin.R_new, sigma_bar);
      b.R[p] = kin.R_new;
      if (b.plastic_work) b.plastic_work[p] = res.plastic_work_density;
    });
  }

  double wave_speed(const FieldStore& store, Index p, double J) const override {
    constexpr int kMaxState = 16;
    double st[kMaxState];
    for (size_t s = 0; s < state_.size(); ++s) st[s] = store.real(state_[s].name)[p];
    return Model::wave_speed(params_, st, J);
  }

 private:
  using Params = typename Model::Params;
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

/// Registers Model under Model::kName; use once per model file at namespace scope.
#define BALLISTA_REGISTER_MATERIAL(Model, Description)                                         \
  namespace {                                                                                  \
  const bool registered_##Model = ::ballista::register_material(::ballista::MaterialFactory{   \
      Model::kName, Description, Model::param_specs(), Model::state_fields(),                  \
      [](const std::string& name, const ::ballista::ParamValues& v)                            \
          -> std::unique_ptr<::ballista::Material> {                                           \
        return std::make_unique<::ballista::MaterialAdapter<Model>>(name, Model::make(v));     \
      }});                                                                                     \
  }
}  // namespace ballista
