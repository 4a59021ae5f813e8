#pragma once
// Turns a per-point kernel (see material.hpp) into a Material that updates a batch of points,
// with the failure criteria and erosion of materials/failure.hpp applied after the kernel.
#include <algorithm>
#include <string>
#include <vector>

#include "core/point_fields.hpp"
#include "core/polar.hpp"
#include "materials/distortion.hpp"
#include "materials/eos.hpp"
#include "materials/failure.hpp"
#include "materials/material.hpp"
#include "materials/material_lanes.hpp"
#include "materials/strain_increment.hpp"

namespace ballista {

/// What Model's kernel fills in PointResult (ModelCapabilities; absent flags are false).
template <class Model>
constexpr ModelCapabilities model_capabilities() {
  ModelCapabilities c;
  if constexpr (requires { Model::kTracksPlasticStrain; }) c.plastic_strain = Model::kTracksPlasticStrain;
  if constexpr (requires { Model::kTracksTemperature; }) c.temperature = Model::kTracksTemperature;
  return c;
}

template <class Model>
class MaterialAdapter final : public Material {
 public:
  /// Most state variables a point can have (model + failure); checked at construction.
  static constexpr int kMaxState = 16;

  MaterialAdapter(std::string name, typename Model::Params params, FailureModel failure = {})
      : name_(std::move(name)), params_(params), failure_(failure), state_(model_state_fields(params_)) {
    model_states_ = static_cast<int>(state_.size());
    for (const auto& f : failure_state_fields(failure_)) state_.push_back(f);
    if (state_.size() > static_cast<size_t>(kMaxState))
      throw Error(std::string("material model ") + Model::kName + " has more than 16 state variables");
  }

  const std::string& name() const override { return name_; }
  const char* model() const override { return Model::kName; }
  double density() const override { return params_.density; }
  std::vector<StateFieldSpec> state_fields() const override { return state_; }
  const typename Model::Params& params() const { return params_; }
  const FailureModel& failure() const { return failure_; }
  bool failed_points_are_stress_free() const override {
    return failure_.active() && failure_.erosion == ErosionRule::ZeroStress;
  }
  bool changes_at_rest() const override {
    if constexpr (requires { Model::kChangesAtRest; }) return Model::kChangesAtRest;
    return false;
  }

  Mat3 initial_stress(const Mat3& F) const override {
    Mat3 R, U;
    polar_decompose(F, R, U);
    return initial_stress_impl(F, R);
  }

  /// The failure branch is chosen once per batch, so a material without a criterion pays nothing.
  /// kLanes points at a time (core/lanes.hpp) where the model allows it (material_lanes.hpp: the same results to
  /// round-off; the choice is per material, never per point).
  void update(const MaterialBatch& b) const override {
    if (in_lanes(b))
      update_lanes(b);
    else if (failure_.active())
      update_batch<true>(b);
    else
      update_batch<false>(b);
  }

  double max_signal_speed(const FieldStore& store, const Index* points, Index count) const override {
    const PointWaveSpeed speed(*this, store);
    const Vec3* v = store.view(kVelocity);
    double vmax = 0.0;
#pragma omp parallel for reduction(max : vmax) schedule(static) if (count > kParallelThreshold)
    for (Index k = 0; k < count; ++k) vmax = std::max(vmax, speed(points[k]) + norm(v[points[k]]));
    return vmax;
  }

  void wave_speeds(const FieldStore& store, const Index* points, Index count, double* c) const override {
    const PointWaveSpeed speed(*this, store);
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
    for (Index k = 0; k < count; ++k) c[points[k]] = speed(points[k]);
  }

  void wave_speeds_at(const FieldStore& store, const Index* points, Index count, const double* J,
                      double* c) const override {
    const PointWaveSpeed speed(*this, store, -1, false);
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
    for (Index k = 0; k < count; ++k) c[k] = speed(points[k], J[k]);
  }

  void reference_wave_speeds(const FieldStore& store, const Index* points, Index count, double* c) const override {
    const PointWaveSpeed speed(*this, store, eos_energy_slot());
#pragma omp parallel for schedule(static) if (count > kParallelThreshold)
    for (Index k = 0; k < count; ++k) c[points[k]] = speed(points[k]);
  }

  double wave_speed(const FieldStore& store, Index p, double J) const override {
    return PointWaveSpeed(*this, store, -1, false)(p, J);
  }

 private:
  using Params = typename Model::Params;

  /// The model's wave speed of a point from its state fields and J = det F (the fields looked up
  /// once per batch): shared by max_signal_speed and wave_speeds.
  /// `zero_slot` >= 0: that state slot is read as zero (reference_wave_speeds).
  class PointWaveSpeed {
   public:
    /// with_F false: only operator()(p, J) is called (F is not read, and need not exist).
    PointWaveSpeed(const MaterialAdapter& m, const FieldStore& store, int zero_slot = -1, bool with_F = true)
        : params_(m.params_),
          ns_(read_slots(m)),
          zero_slot_(zero_slot),
          F_(with_F ? store.view(kDeformationGradient) : nullptr) {
      for (int s = 0; s < ns_; ++s) sptr_[s] = store.real(m.state_[s].name);
    }
    double operator()(Index p) const { return (*this)(p, det(F_[p])); }
    /// The same at a given J.
    double operator()(Index p, double J) const {
      double st[kMaxState];
      for (int s = 0; s < ns_; ++s) st[s] = sptr_[s][p];
      if (zero_slot_ >= 0) st[zero_slot_] = 0.0;
      return Model::wave_speed(params_, st, J);
    }

   private:
    /// The state slots the model's wave_speed reads: the leading `wave_speed_state_count` of them
    /// where the model says so (the rest are not fetched: this runs for every point every step),
    /// else all.
    static int read_slots(const MaterialAdapter& m) {
      const int all = static_cast<int>(m.state_.size());
      if constexpr (requires { Model::wave_speed_state_count(m.params_); })
        return std::min(all, Model::wave_speed_state_count(m.params_));
      else
        return all;
    }

    const Params& params_;
    int ns_;
    int zero_slot_;
    const Mat3* F_;
    const double* sptr_[kMaxState] = {};
  };

  /// The lane path covers the per-point loop without tangent or F_n, for dt > 0.
  bool in_lanes(const MaterialBatch& b) const {
    if constexpr (requires { Model::lanes_apply(params_); })
      return !kNeedsFOld && !b.tangent && b.dt > 0.0 && Model::lanes_apply(params_);
    else
      return false;
  }
  void update_lanes(const MaterialBatch& b) const {
    if constexpr (requires { Model::lanes_apply(params_); }) {
      double* sptr[kMaxState];
      const int ns = static_cast<int>(state_.size());
      for (int s = 0; s < ns; ++s) sptr[s] = b.store->real(state_[s].name);
      if (failure_.active())
        update_in_lanes<Model, kMaxState, true>(params_, failure_, model_states_, b, sptr, ns);
      else
        update_in_lanes<Model, kMaxState, false>(params_, failure_, model_states_, b, sptr, ns);
    }
  }

  template <bool kFailure>
  void update_batch(const MaterialBatch& b) const {
    const int ns = static_cast<int>(state_.size());
    std::vector<double*> sptr(ns);
    for (int s = 0; s < ns; ++s) sptr[s] = b.store->real(state_[s].name);
    const Params& prm = params_;
    const FailureModel& fm = failure_;
    const int nm = model_states_;  // failure's damage and failed follow the model's state
    // Balanced: a return-mapping model costs ten times more at its yielding points than at its
    // elastic ones, and points sorted by cell put the yielding ones together (a crater).
    for_each_uneven_local(0, b.count, kParallelThreshold, kPointChunk, [&](Index k) {
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
      kin.time = b.time;
      kin.J_new = det(kin.F_new);
      kin.J_old = kin.J_new / detA;
      const Mat3 R_old = b.R[p];
      // Strain rate handed to the kernel: the midpoint increment of Hughes & Winget 1980 (Int. J.
      // Numer. Meth. Eng. 15:1862-1867; strain_increment.hpp), sym(G (I + G/2)^-1)/dt with
      // G = dt L = dF - I. It is zero for a rigid rotation step, which sym(L) is not (sym(dQ - I) =
      // (cos dtheta - 1) in the plane of rotation: a spurious strain 2 pi^2/N per turn in N steps),
      // and equals sym(L) to first order, so thesis eq. 2.6 is unchanged in the rate limit. L and
      // the F update (eq. 4.9-4.10) are untouched. The stress power below uses the same D.
      // (dt = 0 leaves nothing to integrate; sym(L) is the limit.)
      const Mat3 D = b.dt > 0.0 ? (1.0 / b.dt) * midpoint_strain_increment(b.dt * L) : sym(L);
      kin.R_new = polar_rotation(kin.F_new, R_old);
      if constexpr (!kReadsStretch) {
        if (b.distortion_limit > 0.0 && remap_if_distorted(kin.F_new, kin.J_new, kin.R_new, b.distortion_limit)) {
          b.F_new[p] = kin.F_new;  // distortion.hpp: same J and R
          if (b.distortion_remaps) b.distortion_remaps->fetch_add(1, std::memory_order_relaxed);
        }
      }
      kin.D_bar = unrotate_sym(kin.R_new, D);
      const Mat3 sigma_old = b.stress[p];
      Mat3 sigma_bar = unrotate_sym(R_old, sigma_old);
      [[maybe_unused]] const Mat3 sigma_bar_old = kFailure ? sigma_bar : Mat3{};
      double st[kMaxState];
      for (int s = 0; s < ns; ++s) st[s] = sptr[s][p];
      [[maybe_unused]] double st_old[kMaxState];
      if constexpr (kFailure)
        for (int s = 0; s < nm; ++s) st_old[s] = st[s];
      PointResult res;
      if (b.tangent) res.tangent = b.tangent + 36 * p;
      // A point that failed in an earlier step under zero_stress keeps none of what the kernel
      // would compute (stress, state, F and dissipation are all reset below), so the kernel is not
      // run: debris torn far from its reference state is where a return mapping costs most.
      if (!(kFailure && frozen_when_failed(fm, st[nm + 1]) && !b.tangent)) Model::update(prm, kin, sigma_bar, st, res);
      Mat3 sigma_new = rotate_sym(kin.R_new, sigma_bar);
      if constexpr (kFailure) {
        // Criterion on the kernel's stress at t_{n+1}; erosion (thesis eq. 6.11-6.14) once failed.
        const bool failed = failure_update(fm, sigma_bar_old, sigma_bar, res, b.dt, st[nm], st[nm + 1]);
        if (failed && fm.erosion != ErosionRule::None) {
          erode(fm.erosion, sigma_new);
          // The stress is no longer the model's, nor is its dissipation: the energy released by
          // erosion stays in the stress-power integral (internal energy), not in plastic work.
          res.plastic_work_density = 0.0;
          if (fm.erosion == ErosionRule::ZeroStress) {  // F* = F_n (eq. 6.14): frozen deformation
            b.F_new[p] = (b.F_old || kNeedsFOld) ? kin.F_old : inverse(A) * kin.F_new;
            kin.R_new = R_old;
            kin.J_new = kin.J_old;
            // and with it the model's state (EOS energy, temperature, plastic strain): the kernel
            // advanced it along F_new, which the point does not take. Kept, a squeezed eroded
            // point's Mie-Gruneisen energy grew by p dV every step without its volume changing,
            // and its sound speed with it (35 km/s in tungsten, a 100x smaller time step).
            for (int s = 0; s < nm; ++s) st[s] = st_old[s];
          }
        }
      }
      for (int s = 0; s < ns; ++s) sptr[s][p] = st[s];
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

  /// The model's state variables: per instance if the model has state_fields(params) (e.g. the
  /// EOS energy only with eos.type mie_gruneisen), else its static list.
  static std::vector<StateFieldSpec> model_state_fields(const Params& p) {
    if constexpr (requires { Model::state_fields(p); })
      return Model::state_fields(p);
    else
      return Model::state_fields();
  }
  /// Models that read PointKinematics::F_old declare `static constexpr bool kNeedsFOld = true`.
  static constexpr bool kNeedsFOld = [] {
    if constexpr (requires { Model::kNeedsFOld; }) return Model::kNeedsFOld;
    else return false;
  }();
  /// Hyperelastic models (those with initial_stress(params, F)) read F's isochoric stretch; the
  /// others read only J and R of F, so the distortion limit may remap them.
  static constexpr bool kReadsStretch = requires(const Params& q, const Mat3& F) { Model::initial_stress(q, F); };
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

  /// The model's state slot of the EOS energy density, -1 without one.
  int eos_energy_slot() const {
    for (int s = 0; s < model_states_; ++s)
      if (state_[s].name == kEosEnergyField) return s;
    return -1;
  }

  std::string name_;
  Params params_;
  FailureModel failure_;
  std::vector<StateFieldSpec> state_;  ///< the model's, then failure's
  int model_states_ = 0;
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

template <class Model>
constexpr auto verification_reduce_geo() -> ParamValues (*)(const GeoReduction&) {
  if constexpr (requires { Model::reduce_to_geo(GeoReduction{}); }) return &Model::reduce_to_geo;
  else return nullptr;
}

/// The registry entry of Model: its parameters plus the failure.* group shared by every model,
/// its (static) state fields, and a create() that makes the kernel's Params, then the failure
/// model (ParamError naming the key on bad input), and wraps both in a MaterialAdapter. Tests use
/// it directly to make a material of a test-only kernel without registering it.
template <class Model>
MaterialFactory material_factory(const char* description) {
  std::vector<ParamSpec> params = Model::param_specs();
  for (auto& s : failure_param_specs()) params.push_back(std::move(s));
  return MaterialFactory{
      Model::kName, description, std::move(params), Model::state_fields(),
      [](const std::string& name, const ParamValues& v) -> std::unique_ptr<Material> {
        typename Model::Params p = Model::make(v);
        const FailureModel f = make_failure(v, model_capabilities<Model>());
        return std::make_unique<MaterialAdapter<Model>>(name, p, f);
      },
      verification_example<Model>(), verification_reduce_elastic<Model>(), verification_reduce_j2<Model>(),
      verification_reduce_geo<Model>()};
}

/// Registers Model under Model::kName; use once per model file at namespace scope.
#define BALLISTA_REGISTER_MATERIAL(Model, Description) \
  BALLISTA_REGISTER(::ballista::MaterialRegistry, ::ballista::material_factory<Model>(Description))
}  // namespace ballista
