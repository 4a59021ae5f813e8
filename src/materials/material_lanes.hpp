#pragma once
// The stress update of a batch of points kLanes at a time (core/lanes.hpp: 8 with AVX-512, else 4), for the models that allow
// it (`lanes_apply` below): the strain increment, the polar decomposition, the unrotated frame, the model, the
// rotation back and the energy bookkeeping of MaterialAdapter's per-point loop, each on kLanes
// points per instruction. It evaluates the per-point loop's expressions; the results agree with
// that loop's to round-off (tests/unit/materials/test_material_lanes.cpp), and the choice is made
// per material and per step from the material's parameters and the batch's options, never per
// point, so a run is bitwise reproducible for any thread count, ranks and restarts.
//
// A model takes this path where its
//   static bool lanes_apply(const Params&);   // this parameter set runs kLanes points at a time
// is true; it may add a lane kernel
//   static void update_lanes(const Params&, const LaneKinematics&, Mat3L& sigma_bar, Lane* state,
//                            Lane& plastic_work_density);
// doing for kLanes points what its update() does for one, else its update() runs lane by lane on
// the kinematics computed kLanes at a time (always with a failure criterion, which reads the
// kernel's PointResult). The per-point loop stays for tangents, models that read F_n, and dt = 0.
// A model whose update() runs lane by lane may first offer the lanes to
//   static bool elastic_lanes_apply(const Params&);
//   static LaneMask update_lanes_elastic(const Params&, const LaneKinematics&, LaneMask want,
//                                        Mat3L& sigma_bar, Lane* state, PointResult* res,
//                                        Lane& plastic_work_density);
// which takes the lanes it can update kLanes at a time bitwise as update() would (the geomodel's
// certainly elastic steps), a choice per point that is safe only because it is bitwise; update()
// runs the lanes it leaves.
#include <algorithm>
#include <atomic>
#include <vector>

#include "core/parallel.hpp"
#include "core/polar_lanes.hpp"
#include "materials/distortion.hpp"
#include "materials/failure.hpp"
#include "materials/material.hpp"
#include "materials/strain_increment.hpp"

namespace ballista {

/// What a lane kernel reads of the motion of kLanes points over the step (PointKinematics' D_bar,
/// J_old, J_new and dt).
struct LaneKinematics {
  Mat3L D_bar;  ///< unrotated rate of deformation, 1/s
  Lane J_old;
  Lane J_new;
  double dt = 0.0;
};

/// The kernel's state fields are `state[s]` (indexed by point), `ns` of them (at most kMaxState);
/// with a failure criterion (kFailure) its damage and failed flags are the two after the model's
/// `nm` (failure.hpp), and the model's scalar kernel runs lane by lane, since the criterion reads
/// its PointResult.
template <class Model, int kMaxState, bool kFailure>
void update_in_lanes(const typename Model::Params& prm, const FailureModel& fm, int nm, const MaterialBatch& b,
                     double* const* state, int ns) {
  const Index groups = (b.count + kLanes - 1) / kLanes;
  const double dt = b.dt;
  // Parallel from kParallelThreshold points (not groups: a group is kLanes points' work), in
  // chunks of 512 points, each thread on its own points first (yielding points cost more and
  // cluster: for_each_uneven_local).
  for_each_uneven_local(0, groups, (kParallelThreshold + kLanes - 1) / kLanes, kPointChunk / kLanes, [&](Index g) {
    const Index k0 = g * kLanes;
    const int n = static_cast<int>(std::min<Index>(kLanes, b.count - k0));
    Index idx[kLanes];  // a short last group repeats its last point in the unused lanes
    for (int l = 0; l < kLanes; ++l) idx[l] = b.points[k0 + std::min(l, n - 1)];

    const Mat3L L = gather(b.L, idx);
    Mat3L F_new = gather(b.F_new, idx);
    const Mat3L R_old = gather(b.R, idx);
    // As MaterialAdapter's loop: F_new = (I + dt L) F_old (thesis seed 000 eq. 4.9), J_old from
    // det(I + dt L), the midpoint strain increment (Hughes & Winget 1980; strain_increment.hpp).
    const Mat3L A = Mat3L::identity() + dt * L;
    const Lane detA = det(A);
    LaneKinematics kin;
    kin.dt = dt;
    kin.J_new = det(F_new);
    kin.J_old = kin.J_new / detA;
    const Mat3L D = (1.0 / dt) * midpoint_strain_increment(dt * L);
    Mat3L R_new = polar_rotation(F_new, R_old);
    if (b.distortion_limit > 0.0) {
      // Lanes clearly inside the limit skip the (out-of-line) scalar check, which decides for the
      // rest: the lanes' test of beyond_distortion_limit at 0.99 of the limit cannot miss a point
      // the scalar test would remap, whatever the round-off.
      const LaneMask near = beyond_distortion_limit(F_new, kin.J_new, 0.99 * b.distortion_limit);
      for (int l = 0; l < n; ++l) {
        if (!near[l]) continue;
        Mat3 Fl = F_new.lane(l);
        if (remap_if_distorted(Fl, kin.J_new[l], R_new.lane(l), b.distortion_limit)) {
          b.F_new[idx[l]] = Fl;  // distortion.hpp: same J and R
          F_new.set_lane(l, Fl);
          if (b.distortion_remaps) b.distortion_remaps->fetch_add(1, std::memory_order_relaxed);
        }
      }
    }
    kin.D_bar = unrotate_sym(R_new, D);
    const Mat3L sigma_old = gather(b.stress, idx);
    Mat3L sigma_bar = unrotate_sym(R_old, sigma_old);
    Lane st[kMaxState];
    for (int s = 0; s < ns; ++s) st[s] = gather(state[s], idx);
    [[maybe_unused]] Lane st_old[kMaxState];
    if constexpr (kFailure)
      for (int s = 0; s < nm; ++s) st_old[s] = st[s];
    Lane plastic_work = splat(0.0);
    [[maybe_unused]] const Mat3L sigma_bar_old = sigma_bar;
    [[maybe_unused]] PointResult res[kLanes];
    if constexpr (!kFailure && requires { Model::update_lanes(prm, kin, sigma_bar, st, plastic_work); }) {
      Model::update_lanes(prm, kin, sigma_bar, st, plastic_work);
    } else {
      // A model without a lane kernel (Johnson-Cook: its return needs pow and log per iteration)
      // runs its scalar kernel lane by lane on the kinematics computed kLanes at a time.
      // A model may first take the lanes whose step it can do kLanes at a time bitwise as its
      // update() (the geomodel's elastic steps: update_lanes_elastic); the rest run update().
      LaneMask done{};
      if constexpr (requires { Model::update_lanes_elastic(prm, kin, done, sigma_bar, st, res, plastic_work); }) {
        if (Model::elastic_lanes_apply(prm)) {
          LaneMask want{};
          for (int l = 0; l < kLanes; ++l) {
            want[l] = -1;
            if constexpr (kFailure)
              if (frozen_when_failed(fm, st[nm + 1][l])) want[l] = 0;
          }
          done = Model::update_lanes_elastic(prm, kin, want, sigma_bar, st, res, plastic_work);
        }
      }
      PointKinematics pk;
      pk.dt = dt;
      pk.time = b.time;
      for (int l = 0; l < kLanes; ++l) {
        if (done[l]) continue;
        // As MaterialAdapter's loop: a point failed under zero_stress keeps nothing of the kernel's.
        if constexpr (kFailure)
          if (frozen_when_failed(fm, st[nm + 1][l])) continue;
        pk.F_new = F_new.lane(l);
        pk.R_new = R_new.lane(l);
        pk.D_bar = kin.D_bar.lane(l);
        pk.J_old = kin.J_old[l];
        pk.J_new = kin.J_new[l];
        Mat3 sb = sigma_bar.lane(l);
        double sl[kMaxState];
        for (int s = 0; s < ns; ++s) sl[s] = st[s][l];
        Model::update(prm, pk, sb, sl, res[l]);
        sigma_bar.set_lane(l, sb);
        for (int s = 0; s < ns; ++s) st[s][l] = sl[s];
        plastic_work[l] = res[l].plastic_work_density;
      }
    }
    Mat3L sigma_new = rotate_sym(R_new, sigma_bar);
    if constexpr (kFailure) {
      // As MaterialAdapter's loop: the criterion on the kernel's stress at t_{n+1}; erosion (thesis
      // eq. 6.11-6.14) once failed, with F* = F_n (eq. 6.14) for zero_stress.
      for (int l = 0; l < kLanes; ++l) {
        double damage = st[nm][l], failed_flag = st[nm + 1][l];
        const bool failed =
            failure_update(fm, sigma_bar_old.lane(l), sigma_bar.lane(l), res[l], dt, damage, failed_flag);
        st[nm][l] = damage;
        st[nm + 1][l] = failed_flag;
        if (!failed || fm.erosion == ErosionRule::None) continue;
        Mat3 sl = sigma_new.lane(l);
        erode(fm.erosion, sl);
        sigma_new.set_lane(l, sl);
        plastic_work[l] = 0.0;  // the stress is no longer the model's, nor is its dissipation
        if (fm.erosion == ErosionRule::ZeroStress) {
          if (l < n) b.F_new[idx[l]] = b.F_old ? b.F_old[idx[l]] : inverse(A.lane(l)) * F_new.lane(l);
          R_new.set_lane(l, R_old.lane(l));
          kin.J_new[l] = kin.J_old[l];
          for (int s = 0; s < nm; ++s) st[s][l] = st_old[s][l];  // the model's state frozen with F
        }
      }
    }

    Lane internal_energy, plastic_energy;
    if (b.internal_energy) {
      const Lane V0 = gather(b.volume0, idx);
      const Lane V_new = V0 * kin.J_new;
      const Lane V_old = V0 * kin.J_old;
      internal_energy = gather(b.internal_energy, idx);
      plastic_energy = gather(b.plastic_energy, idx);
      internal_energy += dt * 0.5 * (V_old + V_new) * 0.5 * ddot(sigma_old + sigma_new, D);
      plastic_energy += plastic_work * V_new;
    }
    for (int l = 0; l < n; ++l) {
      const Index p = idx[l];
      for (int s = 0; s < ns; ++s) state[s][p] = st[s][l];
      const Mat3 sl = sigma_new.lane(l);
      b.stress[p] = sl;
      b.R[p] = R_new.lane(l);
      if (b.plastic_work) b.plastic_work[p] = plastic_work[l];
      if (b.internal_energy) {
        b.internal_energy[p] = internal_energy[l];
        b.plastic_energy[p] = plastic_energy[l];
      }
      if (b.first_bad && !all_finite(sl)) {
        Index cur = b.first_bad->load(std::memory_order_relaxed);
        while (p < cur && !b.first_bad->compare_exchange_weak(cur, p, std::memory_order_relaxed)) {
        }
      }
    }
  });
}

}  // namespace ballista
