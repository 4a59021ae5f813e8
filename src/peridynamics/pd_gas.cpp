// The peridynamic solver's detonation products (seed 001 "Gases as Peridynamic
// Materials"): the gas family, the density measure X fed to the shared material library, the
// stable step of the gas and the venting of gas that leaves the box. The pair force itself is in
// gas_pass.cpp; pd_solver.cpp calls these.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>

#include "core/point_fields.hpp"
#include "peridynamics/pd_solver.hpp"

namespace ballista {

void PdSolver::build_gas() {
  // The gas family was built with the bonds (build_local_points); arrays per local point.
  const Index n = local_.size(), nb = local_.bond_local;
  const auto* vol0 = local_.vol0.data();
  gas_local_.assign(static_cast<size_t>(n), 0);
  gas_scale_.assign(static_cast<size_t>(n), 1.0);
  for (Index l = 0; l < n; ++l) {
    gas_local_[l] = gas_material_[local_.material[l]];
    if (gas_local_[l]) gas_scale_[l] = body_scale_[local_.body[l]];
  }
  gas_volume_.assign(static_cast<size_t>(n), 0.0);
  gas_inv_len_.assign(static_cast<size_t>(n), 0.0);
  gas_x_.assign(static_cast<size_t>(n), 1.0);
  gas_g_.assign(static_cast<size_t>(n), 0.0);
  vented_.assign(static_cast<size_t>(n), 0);
  vent_velocity_.assign(static_cast<size_t>(n), Vec3{});
  const pd::GasPassArgs a = gas_pass_args();
  for_each_uneven(0, nb, [&](Index p) {
    if (!gas_local_[p]) return;
    double v = 0.0;
    for (Index k = gas_bonds_.offset[p]; k < gas_bonds_.offset[p + 1]; ++k)
      v += gas_bonds_.volume_factor[k] * vol0[gas_bonds_.other[k]];
    gas_volume_[p] = v;
    gas_inv_len_[p] = pd::gas_inverse_length_sum(a, p);
  });
}

pd::GasPassArgs PdSolver::gas_pass_args() const {
  // Over the local points (own and ghosts; positions from sync_local).
  return {local_.x.data(), local_.vol0.data(), &gas_bonds_, gas_local_.data(), gas_volume_.data(), gas_g_.data(), dim_,
          gas_len_other_.empty() ? nullptr : gas_len_other_.data(),
          gas_weight_other_.empty() ? nullptr : gas_weight_other_.data()};
}

void PdSolver::update_gas(double dt) {
  const Index n = points_.size();
  auto* F = points_.view(kDeformationGradient);
  auto* L = points_.view(kVelocityGradient);
  auto* volume = points_.real(kVolume);
  const auto* vol0 = points_.real(kReferenceVolume);
  const pd::GasPassArgs a = gas_pass_args();
  const double inv_d = 1.0 / dim_;
  const Index* own = local_.own.data();
  std::atomic<Index> limited{0};
  // X at t_{n+1}; the deformation the material sees is the isotropic F = X^(1/d) (in the plane
  // in 2D), reached from the old one by L = a I over dt, (1 + a dt)^d = X_new / X_old, so that
  // the adapter's F_old = (I + dt L)^-1 F_new and J_old = X_old are exact.
  for_each_uneven(0, n, [&](Index p) {
    const Index l = own[p];  // the gas arrays are per local point
    if (!gas_[p] || vented_[l]) {
      if (gas_[p]) L[p] = Mat3{};
      return;
    }
    // A gas point left without neighbours (the renewal finds none: the products have spread past
    // its reach) measures nothing and pushes nothing: it keeps its X. Read as X = 1, it would be
    // recompressed to its reference density, its pressure work booked as internal energy that
    // nothing did.
    const double x_old = gas_x_[l];
    const double x_measured = a.family_volume[l] > 0.0 ? pd::density_measure(a, l) : x_old;
    const double x_new = std::clamp(x_measured, x_old / pd::kGasMaxStepRatio, x_old * pd::kGasMaxStepRatio);
    if (x_new != x_measured) limited.fetch_add(1, std::memory_order_relaxed);
    const double s = std::pow(x_new, inv_d), rate = dt > 0.0 ? (std::pow(x_new / x_old, inv_d) - 1.0) / dt : 0.0;
    Mat3 f = Mat3::identity(), lg;
    for (int d = 0; d < dim_; ++d) {
      f(d, d) = s;
      lg(d, d) = rate;
    }
    F[p] = f;
    L[p] = lg;
    gas_x_[l] = x_new;
    volume[p] = vol0[p] * x_new;
  });
  gas_rate_limited_ += limited.load();
  // The products' pressure through the library: program burn, JWL / ideal gas, energy -P dV.
  pts_.update_stress(dt, steps_ + 1, time_ + dt, gas_material_);
  if (params_.gas_refamily_steps > 0 && (steps_ + 1) % params_.gas_refamily_steps == 0) refamily_gas();
  // G_i = d P_i X_i^(1+m/d) dV0_i / V_i (gas_pass.hpp); a vented point pushes nothing.
  const auto* stress = points_.view(kStress);
  const double expo = 1.0 + pd::kGasExponent / dim_;
  for_each(0, n, [&](Index p) {
    if (!gas_[p]) return;
    const Index l = own[p];
    const double P = -trace(stress[p]) / 3.0;
    gas_g_[l] = vented_[l] || !(gas_volume_[l] > 0.0)
                    ? 0.0
                    : dim_ * P * std::pow(gas_x_[l], expo) * vol0[p] / gas_volume_[l];
  });
}

void PdSolver::refamily_gas() {
  // The inputs are kept: a restart builds the same family from them (pd_checkpoint.cpp).
  renewal_.x = local_.x;
  renewal_.X = gas_x_;
  renewal_.skip = vented_;
  build_renewed_gas_family();
}

void PdSolver::build_renewed_gas_family() {
  // Built into the spare storage (the family before last: its pages are mapped), then swapped in.
  pd::build_renewed_gas_family(renewal_.x.data(), local_.size(), gas_local_.data(), renewal_.skip.data(),
                               renewal_.X.data(), delta_, dim_, gas_spare_, gas_workspace_,
                               max_scale_ > 1.0 ? gas_scale_.data() : nullptr);
  std::swap(gas_bonds_, gas_spare_.family);
  std::swap(gas_len_other_, gas_spare_.length_other);
  std::swap(gas_weight_other_, gas_spare_.weight_other);
  ++gas_renewals_;
  const Index n = local_.size();
  const auto* vol0 = local_.vol0.data();
  const pd::GasPassArgs a = gas_pass_args();
  for_each_uneven(0, n, [&](Index p) {
    if (!gas_local_[p]) return;
    double v = 0.0, v0 = 0.0;
    for (Index k = gas_bonds_.offset[p]; k < gas_bonds_.offset[p + 1]; ++k) {
      v += gas_bonds_.volume_factor[k] * vol0[gas_bonds_.other[k]];
      v0 += vol0[gas_bonds_.other[k]];
    }
    gas_volume_[p] = v;
    // The stable step's sum with the weights divided by their mean: G_i carries 1/V_i, so the
    // current-volume weights scale each bond's stiffness by w_j / mean(w), not by w_j.
    gas_inv_len_[p] = v > 0.0 ? pd::gas_inverse_length_sum(a, p) * v0 / v : 0.0;
  });
}

double PdSolver::gas_stable_dt() const {
  // Silling & Askari 2005 eq. 17, dt < sqrt(2 rho0 / sum_j V_j c/|xi|), with the micromodulus of
  // a PMB solid of the products' current bulk modulus K = rho c^2 = rho0 c^2 / X (c = 18 K/m1 in
  // 3D, 8 K/m1 in 2D: the calibration of the solid bonds, pd_solver.cpp). Linearised about a
  // uniform state, the gas bond's stiffness is that of the pressure's dependence on X, which is
  // this K; the reference lengths are kept (the spacing only grows as the gas expands). A gas
  // lattice `a` times coarser has the moment m1 a^(d+1) of its horizon (m1 ~ delta^(d+1)).
  // The safety factor is applied here and again in stable_dt (0.64 for the gas with the default
  // 0.8), on purpose: with it once, the Gurney cylinder of tests/verification/test_pd_gas.cpp
  // (0.5 mm, M/C = 1) closes its energy balance to 3.0 % of the chemical energy instead of 1.5 %,
  // over the 2 % that test allows; the linearised bound does not hold the products'
  // nonlinear stiffening near the front.
  const Index n = points_.size();
  const auto* mat = points_.ints(kMaterialIndex);
  const auto& mats = pts_.materials();
  const double coef = dim_ == 3 ? 18.0 : 8.0;
  const Index* own = local_.own.data();
  double dt = std::numeric_limits<double>::infinity();
  // The wave speeds a material at a time, at J = X (its fields looked up once, not per point).
  GasStepScratch& w = gas_step_scratch_;
  w.points.resize(mats.size());
  w.X.resize(mats.size());
  for (size_t m = 0; m < mats.size(); ++m) w.points[m].clear(), w.X[m].clear();
  for (Index p = 0; p < n; ++p) {
    const Index l = own[p];
    if (!gas_[p] || vented_[l] || !(gas_inv_len_[l] > 0.0)) continue;
    w.points[static_cast<size_t>(mat[p])].push_back(p);
    w.X[static_cast<size_t>(mat[p])].push_back(gas_x_[l]);
  }
  for (size_t m = 0; m < mats.size(); ++m) {
    const Index count = static_cast<Index>(w.points[m].size());
    if (count == 0) continue;
    const Index* pts = w.points[m].data();
    const double* Xm = w.X[m].data();
    w.c.resize(static_cast<size_t>(count));
    mats[m]->wave_speeds_at(points_, pts, count, Xm, w.c.data());
#pragma omp parallel for schedule(static) reduction(min : dt) if (count > kParallelThreshold)
    for (Index k = 0; k < count; ++k) {
      const Index l = own[pts[k]];
      const double X = Xm[k], c = w.c[k];
      // rho0 / (coef rho0 c^2 / (X m1) * sum) = X m1 / (coef c^2 sum)
      const double m1 = m1_ * std::pow(gas_scale_[l], dim_ + 1);
      if (c > 0.0) dt = std::min(dt, std::sqrt(2.0 * X * m1 / (coef * c * c * gas_inv_len_[l])));
    }
  }
  return comm_.min(params_.dt_safety * dt);
}

void PdSolver::vent_escaped_gas() {
  const Index n = points_.size();
  auto* x = points_.view(kPosition);
  auto* v = points_.view(kVelocity);
  auto* eint = points_.real(kInternalEnergy);
  const GridSpec& g = scenario_.grid;
  for (Index p = 0; p < n; ++p) {
    const Index l = local_.own[p];
    if (!gas_[p] || vented_[l]) continue;
    if (g.contains(x[p])) continue;
    pts_.book_vented(p);
    vented_[l] = 1;
    ++vented_count_;
    vented_since_build_ = true;
    vent_velocity_[l] = v[p];  // it flies on (pd_solver.cpp), out of the balance
    v[p] = Vec3{};
    eint[p] = 0.0;
    gas_g_[l] = 0.0;
  }
}

}  // namespace ballista
