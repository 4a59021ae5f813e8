#include "mpm/mpm_solver.hpp"
#include "mpm/gradient_linear_3d.hpp"
#include "mpm/p2g_linear_3d.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/agreed_failure.hpp"
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "mpm/axis_hoop.hpp"
#include "mpm/graded_shape_functions.hpp"
#include "mpm/mpm_params.hpp"
#include "points/point_exchange.hpp"
#include "points/solver_registry.hpp"

namespace ballista {

namespace {

/// Records the smallest offending index seen by any thread (deterministic for any thread count).
void record_min(std::atomic<Index>& slot, Index p) {
  Index cur = slot.load(std::memory_order_relaxed);
  while (p < cur && !slot.compare_exchange_weak(cur, p, std::memory_order_relaxed)) {
  }
}

/// The weights of one particle for every shape function but GIMP, whose stencils come from the
/// windows kept for the step (MpmSolver::point_stencil). G: the grid is graded
/// (mpm/graded_shape_functions.hpp; no cubic B-spline there, the solver refuses it).
template <int Dim, ShapeKind K, bool G>
inline void stencil_of(const GridGeometry& g, const SplineFaces& faces, const Vec3& x, const Vec3& half,
                       const Mat3& F, Stencil<Dim>& s) {
  static_assert(!(G && K == ShapeKind::BSpline3), "no cubic B-spline on a graded grid");
  static_assert(K != ShapeKind::Gimp, "GIMP stencils come from MpmSolver::point_stencil");
  if constexpr (K == ShapeKind::Linear) {
    if constexpr (G) graded_linear_stencil<Dim>(g, x, s);
    else linear_stencil<Dim>(g, x, s);
  } else if constexpr (K == ShapeKind::BSpline3) {
    bspline3_stencil<Dim>(g, x, s, faces);
  } else {
    // CPDI1 domain vectors r_j = F (half_j e_j) (Sadeghirad et al. 2011, eq. 11).
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r(i, j) = F(i, j) * half[j];
    if constexpr (G) graded_cpdi_stencil<Dim>(g, x, r, s);
    else cpdi_stencil<Dim>(g, x, r, s);
  }
}

/// Whether a uGIMP particle's domain may reach across the axis, decided without the domain's
/// effective half-length l (axis_hoop.hpp): a uniform grid's domains are at most h/2 long; on a
/// graded grid l = min(max(l_p, 1e-12 h_c), h_c / 2) for the local cells h_c, so l <= l_p once l_p
/// exceeds 1e-12 of the grid's radial extent (which bounds h_c). False means r >= l: the plain
/// w_k / r applies, exactly as axis_hoop_weights would decide.
inline bool may_cross_axis(const GridGeometry& g, const Vec3& x, const Vec3& half) {
  if (!g.graded) return x[0] < 0.5 * g.h;
  if (x[0] < half[0]) return true;
  const GradedAxis& radial = (*g.graded)[0];
  return half[0] < 1e-12 * (radial.at(g.nodes[0] - 1) - radial.at(0));
}

/// The hoop operator of an axisymmetric uGIMP particle whose domain crosses the axis
/// (mpm/axis_hoop.hpp); false (use w_k / r) for every other particle and shape function.
template <int Dim, ShapeKind K>
inline bool hoop_near_axis(const GridGeometry& g, const Vec3& x, const Vec3& half, const Stencil<Dim>& st,
                           double* hoop) {
  if constexpr (Dim == 2 && K == ShapeKind::Gimp) {
    if (!may_cross_axis(g, x, half)) return false;
    return axis_hoop_weights(g, x[0], half[0], st, hoop);
  } else {
    return false;
  }
}

/// The hoop rate of such a particle from the node velocities `field` of its velocity field.
template <int Dim, ShapeKind K>
inline bool hoop_rate_near_axis(const GridGeometry& g, const Vec3& x, const Vec3& half, const Stencil<Dim>& st,
                                const Vec3* field, double& rate) {
  if constexpr (Dim == 2 && K == ShapeKind::Gimp) {
    if (!may_cross_axis(g, x, half)) return false;
    return axis_hoop_rate(g, x[0], half[0], st, field, rate);
  } else {
    return false;
  }
}

/// The weights at a surface-traction point: a point load, so the kernel itself (the cubic
/// B-spline, or the linear hat for every other shape function), not a particle domain.
template <int Dim, ShapeKind K, bool G>
inline void surface_point_stencil(const GridGeometry& g, const SplineFaces& faces, const Vec3& x, Stencil<Dim>& s) {
  if constexpr (K == ShapeKind::BSpline3) bspline3_stencil<Dim>(g, x, s, faces);
  else if constexpr (G) graded_linear_stencil<Dim>(g, x, s);
  else linear_stencil<Dim>(g, x, s);
}

}  // namespace

Index MpmSolver::cut_and_migrate() {
  const std::vector<int> dest = partition_.partition(points_.view(kPosition), points_.ints(kId), points_.size());
  const Index moved = migrate_points(comm_, points_, dest);
  pts_.mark_reordered();
  return moved;
}

void MpmSolver::redistribute() {
  // Particles move less than a cell per step, so few cross a cut; the owner of a position is
  // known from the kept cuts without communication (points/rcb_partition.hpp).
  std::vector<int> dest;
  partition_.owners(points_.view(kPosition), points_.size(), dest);
  Index moved = migrate_points(comm_, points_, dest);
  const double n = static_cast<double>(points_.size());
  const double total = comm_.sum(n), largest = comm_.max(n);
  const double mean = total / comm_.size();
  const double imbalance = mean > 0.0 ? largest / mean - 1.0 : 0.0;
  max_imbalance_ = std::max(max_imbalance_, imbalance);
  // Penetration runs move work along the axis: new cuts from the particles where they are now,
  // when the imbalance passes the deck's threshold and has grown by that much since the last
  // repartition (a clump RCB cannot split, or fewer particles than ranks, would otherwise
  // repartition every step).
  if (imbalance > rebalance_ && imbalance > imbalance_after_partition_ + rebalance_) {
    const int before = partition_.partitions();
    moved += cut_and_migrate();
    if (partition_.partitions() > before) ++repartitions_;
    const double m = comm_.max(static_cast<double>(points_.size()));
    imbalance_after_partition_ = mean > 0.0 ? m / mean - 1.0 : 0.0;
  }
  const std::int64_t all_moved = comm_.sum(static_cast<std::int64_t>(moved));
  migrated_ += static_cast<double>(all_moved);
  if (moved > 0) sort_by_cell();
}

void MpmSolver::begin_stage(int stage, double damping) {
  pts_.begin_stage(stage, time_);
  damping_ = damping;
}

double MpmSolver::reporting_scale() const {
  return dimension_ == Dimension::Axisymmetric ? 2.0 * std::numbers::pi : 1.0;
}

void MpmSolver::activate_pending() {
  const bool added = pts_.activate(time_);
  if (added) sort_by_cell();
  // Several ranks: whether any rank added particles that may lie outside its region.
  activated_this_step_ = comm_.distributed() && comm_.any(added);
}

template <int Dim, ShapeKind K, bool G>
[[gnu::always_inline]] inline void MpmSolver::point_stencil(Index p, const Vec3& x, const Vec3& half,
                                                            Stencil<Dim>& st) {
  // Inlined always: it runs per point in every transfer loop. Patches take their own,
  // out-of-line path, which keeps this one small.
  if constexpr (K == ShapeKind::Gimp) {
    // uGIMP: reference half-size (Bardenhagen & Kober 2004).
    GimpWindows<Dim>& w = gimp_windows_of_points<Dim>()[p];
    if constexpr (G) {
      if (!level_geom_.empty()) {
        patch_point_stencil<Dim>(p, x, half, w, st);
        return;
      }
    }
    if (!windows_current_) {
      if constexpr (G) graded_gimp_windows<Dim>(grid_.geom, x, half, w);
      else gimp_windows<Dim>(grid_.geom, x, half, w);
    }
    stencil_from_windows<Dim>(grid_.geom, w, st);
  } else {
    stencil_of<Dim, K, G>(grid_.geom, spline_faces_, x, half, F_[p], st);
  }
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::particles_to_grid(P2gPart part, const Vec3* v_source, Index begin, Index end) {
  const GridGeometry& g = grid_.geom;
  const auto* x = points_.view(kPosition);
  const auto* v = v_source ? v_source : points_.view(kVelocity);
  const auto* half = points_.view(kHalfSize);
  const auto* mass = points_.real(kMass);
  const auto* vol = points_.real(kVolume);
  const auto* stress = points_.view(kStress);
  double* gm = grid_.mass.data();
  Vec3* gp = grid_.velocity.data();
  Vec3* gf = grid_.force.data();
  const bool multi = grid_.fields > 1;
  Vec3* gg = multi ? grid_.grad.data() : nullptr;
  double* gv = grid_.with_volume ? grid_.volume.data() : nullptr;
  const bool mass_part = maps_mass(part), momentum_part = maps_momentum(part), force_part = maps_forces(part);
  if (!maps_volume(part)) gv = nullptr;
  // Only the blocks particles reach are cleared: the others are zero already (active_blocks.hpp).
  // The sums this pass does not form are left as they are.
  for (int k = 0; k < grid_.fields; ++k)
    blocks_.for_each_run(k * g.node_count(), [&](Index b, Index e) {
      if (mass_part) {
        std::fill(gm + b, gm + e, 0.0);
        if (multi) std::fill(gg + b, gg + e, Vec3{});
      }
      if (force_part) std::fill(gf + b, gf + e, Vec3{});
      if (gv) std::fill(gv + b, gv + e, 0.0);
      if (momentum_part) std::fill(gp + b, gp + e, Vec3{});
    });
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  // The contact normal's gradient of the density, not of the mass per radian (scenario.hpp,
  // ContactSpec::axisymmetric_normal): m_p / r_p = rho_p A_p.
  const bool density_normal = multi && axisym && scenario_.contact.axisymmetric_normal == "density";
  const double* bq = bulk_viscosity_.active() ? points_.real(kBulkViscosity) : nullptr;
  if (force_part && anti_locking_ == AntiLocking::FBar) {
    // The F-bar's forces read the averaged pressure (mean dilatation, anti_locking.hpp); it
    // includes the bulk viscosity.
    fbar_.force_pressure(g, {points_.size(), x, vol, stress, bq, points_.ints(kMaterialIndex),
                             static_cast<int>(pts_.materials().size())}, force_pressure_, fbar_across_ranks());
    bq = force_pressure_.data();
  }
  const std::vector<Vec3>& fext = loads_.total();
  const std::vector<Vec3>& ftrac = loads_.traction();
  const bool has_ext = !fext.empty();
  const bool has_trac = force_part && !ftrac.empty();
  const int nslab = static_cast<int>(slab_start_.size()) - 1;
  if (has_trac) {
    // Tractions at the surface points, with the kernel's weights there (serial: few points).
    Stencil<Dim> st;
    for (const PointLoads::SurfaceForce& sf : loads_.surface_forces()) {
      if (sf.index < begin || (end >= 0 && sf.index >= end)) continue;  // another range's point
      surface_point_stencil<Dim, K, G>(g, spline_faces_, sf.point, st);
      const Index fo = field_offset(sf.index);
      for (int k = 0; k < st.count; ++k) gf[fo + st.node[k]] += st.w[k] * sf.force;
    }
  }
  bool done = false;
  if constexpr (K == ShapeKind::Linear && Dim == 3 && !G) {
    if (!multi && !gv) {
      // Eight nodes per vector (mpm/p2g_linear_3d.hpp): the grid bitwise that of the loop below.
      p2g_linear_3d({.g = &g,
                     .slab_start = slab_start_.data(),
                     .slab_points = slab_points_.data(),
                     .nslab = nslab,
                     .x = x,
                     .v = v,
                     .mass = mass,
                     .vol = vol,
                     .stress = stress,
                     .bq = bq,
                     .fext = has_ext ? fext.data() : nullptr,
                     .ftrac = has_trac ? ftrac.data() : nullptr,
                     .part = part,
                     .parallel = points_.size() > kParallelThreshold,
                     .gm = gm,
                     .gp = gp,
                     .gf = gf});
      done = true;
    }
  }
  // Each node receives its sums in point order, whatever the part.
  for (int color = 0; color < 2 && !done; ++color) {
#pragma omp parallel for schedule(dynamic, 1) if (points_.size() > kParallelThreshold)
    for (int s = color; s < nslab; s += 2) {
      Stencil<Dim> st;
      for (Index q = slab_start_[s]; q < slab_start_[s + 1]; ++q) {
        const Index p = slab_points_[q];
        point_stencil<Dim, K, G>(p, x[p], half[p], st);
        const double m = mass[p];
        const Vec3 mv = m * v[p];
        const Index fo = field_offset(p);
        if (part == P2gPart::Momentum) {
          for (int k = 0; k < st.count; ++k) gp[fo + st.node[k]] += st.w[k] * mv;
          continue;
        }
        // The contact normal's weight (grid_contact.hpp): the mass per radian, or that over the
        // point's radius (its half-size nearer the axis, where r_p -> 0 would blow it up).
        const double mg = density_normal ? m / std::max(x[p][0], half[p][0]) : m;
        if (!force_part) {  // P2gPart::Kinematics
          for (int k = 0; k < st.count; ++k) {
            const Index I = fo + st.node[k];
            const double w = st.w[k];
            if (multi) {
              gg[I] += mg * st.grad[k];
              if (gv) gv[I] += w * vol[p];
            }
            gm[I] += w * m;
            gp[I] += w * mv;
          }
          continue;
        }
        // f_I = -V_p sigma_p grad N_I + N_I f_ext,p (Sulsky et al. 1994, eq. 14); axisymmetric
        // adds the hoop term -V_p sigma_tt N_I / r_p to the radial force (per-radian volume; its
        // domain average for a uGIMP domain across the axis, mpm/axis_hoop.hpp). The
        // bulk viscosity's pressure q acts beside the material's stress: sigma - q I (with the
        // F-bar, bq holds what replaces the pressure by its cell average).
        Mat3 Vs = vol[p] * stress[p];
        if (bq)
          for (int i = 0; i < 3; ++i) Vs(i, i) -= vol[p] * bq[p];
        const double hoop = axisym ? Vs(2, 2) / x[p][0] : 0.0;
        double near_axis[Stencil<Dim>::kMax];
        const bool crosses_axis = axisym && hoop_near_axis<Dim, K>(g, x[p], half[p], st, near_axis);
        // Surface tractions are spread from their own points below.
        const Vec3 fe = has_ext ? (has_trac ? fext[p] - ftrac[p] : fext[p]) : Vec3{};
        for (int k = 0; k < st.count; ++k) {
          const Index I = fo + st.node[k];
          const double w = st.w[k];
          const Vec3& dN = st.grad[k];
          if (multi) {
            // The outward vector of the field: the contact normal (grid_contact.hpp).
            if (mass_part) gg[I] += mg * dN;
            if (gv) gv[I] += w * vol[p];  // how much of the node the field fills (contact's gap check)
          }
          if (mass_part) {
            gm[I] += w * m;
            gp[I] += w * mv;
          }
          Vec3 f;
          for (int i = 0; i < 3; ++i)
            f[i] = w * fe[i] - (Vs(i, 0) * dN[0] + Vs(i, 1) * dN[1] + Vs(i, 2) * dN[2]);
          f[0] -= crosses_axis ? Vs(2, 2) * near_axis[k] : hoop * w;
          gf[I] += f;
        }
      }
    }
  }
  if (comm_.distributed()) {
    // Partial sums of the blocks shared with other ranks, added in rank order (grid_exchange.hpp).
    std::vector<GridExchange::Array> arrays;
    if (mass_part) arrays.push_back({gm, 1});
    if (momentum_part) arrays.push_back({reinterpret_cast<double*>(gp), 3});
    if (force_part) arrays.push_back({reinterpret_cast<double*>(gf), 3});
    if (multi && mass_part) arrays.push_back({reinterpret_cast<double*>(gg), 3});
    if (gv) arrays.push_back({gv, 1});
    exchange_.sum(comm_, arrays, grid_.fields);
    halo_bytes_ += static_cast<double>(exchange_.last_bytes());
    halo_messages_ += static_cast<double>(exchange_.last_messages());
    if (part != P2gPart::Momentum) halo_steps_ += 1.0;
  }
  if (!patch_.empty()) fold_patch_nodes(part);
  if (!mirror_faces_.empty()) fold_mirror_faces(part);
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::xpic_velocity(double dt) {
  // XPIC(m) (Hammerquist & Nairn, CMAME 318 (2017) 724, eqs. 27-30; the recursion of NairnMPM's
  // XPICExtrapolationTask): with A = S+ S the grid -> particle -> grid map (interpolation, then the
  // mass-weighted projection), v* = sum_{k=1..m} (-1)^(k+1) C(m,k) A^(k-1) v, the truncated series
  // of A^-1 applied to the lumped grid velocity v. S v* is the part of the particle velocities the
  // grid can carry, without their null-space noise; PIC (m = 1) takes S v and so also damps the
  // carried part. The PIC share of the update then uses v* + dt a (a: this step's constrained
  // acceleration, contact impulses included), under the same face and axis conditions.
  const GridGeometry& g = grid_.geom;
  const Index nall = g.node_count() * grid_.fields;
  const int m = xpic_order_;
  const Index n = points_.size();
  const auto* half = points_.view(kHalfSize);
  xpic_.prev.resize(nall);
  xpic_.target.resize(nall);
  xpic_.at_points.resize(n);
  Vec3* prev = xpic_.prev.data();
  Vec3* star = xpic_.target.data();
  // k = 1: C(m,1) v; v = v_new - dt a is the mapped velocity the update started from.
  for_each_active_node([&](Index i) {
    prev[i] = static_cast<double>(m) * (grid_.velocity_new[i] - dt * grid_.accel[i]);
    star[i] = prev[i];
  });
  double sign = -1.0;
  for (int k = 2; k <= m; ++k) {
    if (!mirror_faces_.empty()) fill_mirror_ghosts(prev);
    // Interpolate to the points, then map back (momentum pass into grid_.velocity, which update_grid
    // no longer needs), times C(m,k) / C(m,k-1) = (m - k + 1) / k.
    for_each(0, n, [&](Index p) {
      Stencil<Dim> st;
      point_stencil<Dim, K, G>(p, x_[p], half[p], st);
      const Index fo = field_offset(p);
      Vec3 u;
      for (int j = 0; j < st.count; ++j) u += st.w[j] * prev[fo + st.node[j]];
      xpic_.at_points[p] = u;
    });
    particles_to_grid<Dim, K, G>(P2gPart::Momentum, xpic_.at_points.data());
    const double scale = static_cast<double>(m - k + 1) / k;
    for_each_active_node([&](Index i) {
      const double mi = grid_.mass[i];
      prev[i] = mi > kTinyMass ? (scale / mi) * grid_.velocity[i] : Vec3{};
      star[i] += sign * prev[i];
    });
    sign = -sign;
  }
  for_each_active_node([&](Index i) { star[i] += dt * grid_.accel[i]; });
  apply_velocity_bcs(star);
  if (!mirror_faces_.empty()) fill_mirror_ghosts(star);
}

inline void MpmSolver::finish_point(Index p, const Mat3& l, const Vec3& disp, double dt,
                                    std::atomic<Index>& bad, std::atomic<Index>& out) {
  L_[p] = l;
  Vec3& x = x_[p];
  x += disp;
  // F_{n+1} = (I + dt L) F_n (thesis seed 000 eq. 4.9); volume from J = det F.
  const Mat3 F = (Mat3::identity() + dt * l) * F_[p];
  const double J = det(F);
  // Every entry of F enters det F, so a NaN or infinite entry leaves J NaN or infinite: J finite
  // and positive is F finite and not inverted (an overflowing J, of a finite F, is refused too).
  if (!(J > 0.0 && J <= std::numeric_limits<double>::max())) [[unlikely]] {
    if (pts_.failed_stress_free(p)) {
      // A point eroded under zero_stress keeps F_n (thesis eq. 6.14: its stress update puts F_n
      // back whatever the increment). An inverting increment of such a stress-free point, which
      // nothing resists, is the grid's, not the material's: it is discarded here (the point moves,
      // its F, volume and state stay), instead of stopping the run. Counted in the summary.
      L_[p] = Mat3{};
      vol_[p] = vol0_[p] * det(F_[p]);
      frozen_discarded_.fetch_add(1, std::memory_order_relaxed);
    } else {
      F_[p] = F;
      vol_[p] = vol0_[p] * J;
      record_min(bad, p);
    }
  } else {
    F_[p] = F;
    vol_[p] = vol0_[p] * J;
  }
  for (int a = 0; a < dim_; ++a)
    if (!(x[a] >= layout_.box_lower[a] && x[a] <= layout_.box_upper[a])) record_min(out, p);
}

// GCC 12 cannot see that stencil_of writes the first st.count entries it reads back in the XPIC
// loop below and warns that the stencil "may be used uninitialized"; the stencils stay
// uninitialised on purpose (they are filled per point in the hot loop).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
template <int Dim, ShapeKind K, bool G, bool Usavg>
void MpmSolver::grid_to_particles(double dt, Index begin, Index end) {
  // One pass per point: grid velocity, acceleration and velocity gradient at the point; FLIP/PIC
  // velocity update; position, F and volume update (USL); failure and exit detection. USAVG's
  // bookkeeping is compiled into its own instance (Usavg), so the USL/MUSL pass stays as lean as
  // it was.
  const GridGeometry& g = grid_.geom;
  auto* v = points_.view(kVelocity);
  const auto* half = points_.view(kHalfSize);
  const Vec3* vn = grid_.velocity_new.data();
  const Vec3* ga = grid_.accel.data();
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  const std::vector<Vec3>& fext = loads_.total();
  const bool has_ext = !fext.empty();
  const bool defer = musl_;  // MUSL: L, F and positions after the second projection
  const double f_dt = Usavg ? 0.5 * dt : dt;  // USAVG: the second half of the strain increment
  constexpr bool exact_transfer = Usavg;
  [[maybe_unused]] const Vec3* vs = Usavg ? usavg_start_.data() : nullptr;
  [[maybe_unused]] const std::vector<Vec3>& ftrac = loads_.traction();
  [[maybe_unused]] const bool has_trac = !ftrac.empty();
  const double flip = flip_;
  const bool xpic = xpic_active();
  // Patches imply a graded grid: on a uniform one (G false) the PIC share's cell look-up below is
  // compiled out of the loop.
  const bool by_cell = G && pic_by_cell();
  const Vec3* vx = xpic ? xpic_.target.data() : nullptr;
  const Index n = points_.size();
  if (defer) displacement_.resize(n);
  const auto* mass = points_.real(kMass);
  std::atomic<Index> bad{n}, out{n};
  double pw[2];
  deterministic_sum<2>(begin, end < 0 ? n : end, [&](Index p, double* o) {
    Stencil<Dim> st;
    const Vec3 xp = x_[p];
    point_stencil<Dim, K, G>(p, xp, half[p], st);
    const Index fo = field_offset(p);
    Vec3 vg, acc;
    Mat3 l;
    for (int k = 0; k < st.count; ++k) {
      const Index I = fo + st.node[k];
      const Vec3& u = vn[I];
      const double w = st.w[k];
      vg += w * u;
      acc += w * ga[I];
      // MUSL takes L from the second projection (velocity_gradient_from_grid), not from here.
      if (defer) continue;
      const Vec3& dN = st.grad[k];
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j) l(i, j) += u[i] * dN[j];
    }
    // Axisymmetric hoop rate v_r / r (thesis seed 000 ch. 5: Uintah's axisymmetric MPM); for a
    // uGIMP domain across the axis its domain average (mpm/axis_hoop.hpp).
    if (axisym && !defer) {
      double rate;
      l(2, 2) = hoop_rate_near_axis<Dim, K>(g, xp, half[p], st, vn + fo, rate) ? rate : vg[0] / xp[0];
    }
    const Vec3 v_old = v[p];
    // FLIP/PIC blend: flip (v + dt a) + (1 - flip) v_grid (Brackbill & Ruppel 1986 FLIP); with
    // XPIC(m) the PIC share is S (v* + dt a) instead of S (v + dt a) (xpic_velocity).
    if (xpic) {
      Vec3 vpic;
      for (int k = 0; k < st.count; ++k) vpic += st.w[k] * vx[fo + st.node[k]];
      v[p] = flip * (v_old + dt * acc) + (1.0 - flip) * vpic;
    } else if (by_cell) {
      const double pic = pic_share_by_cell(xp);
      v[p] = (1.0 - pic) * (v_old + dt * acc) + pic * vg;
    } else {
      v[p] = flip * (v_old + dt * acc) + (1.0 - flip) * vg;
    }
    if constexpr (exact_transfer) {
      if (has_ext) {
        // USAVG: the loads work on the grid, at the nodes' velocity of the step, (v_n + v_end) / 2,
        // as the grid's kinetic-energy identity counts them (tractions below, at their own points).
        Vec3 vm;
        for (int k = 0; k < st.count; ++k) {
          const Index I = fo + st.node[k];
          vm += (0.5 * st.w[k]) * (vs[I] + vn[I]);
        }
        o[0] += dot(has_trac ? fext[p] - ftrac[p] : fext[p], vm);
      }
    } else if (has_ext) {
      o[0] += dot(fext[p], 0.5 * (v_old + v[p]));
    }
    // What the PIC share of the blend takes from the kinetic energy of the pure FLIP update
    // (FLIP alone conserves it to the order of the time step; PIC damps the grid's null space).
    // USAVG books the whole transfer instead: the particles' kinetic-energy change here, less the
    // grid's (grid_kinetic_energy_change), so that the energy balance closes.
    if constexpr (exact_transfer) {
      o[1] += 0.5 * mass[p] * (dot(v[p], v[p]) - dot(v_old, v_old));
    } else if (flip < 1.0) {
      const Vec3 v_flip = v_old + dt * acc;
      o[1] += 0.5 * mass[p] * (dot(v[p], v[p]) - dot(v_flip, v_flip));
    }
    // Positions move with the grid velocity (x += dt sum N_I v_I).
    if (defer) {
      displacement_[p] = dt * vg;
      return;
    }
    if constexpr (exact_transfer) {
      // USAVG moves the point with the velocity whose two halves its strain took, (v_n + v_end)
      // / 2, so that x and F stay consistent (position Verlet within the step).
      Vec3 vm;
      for (int k = 0; k < st.count; ++k) {
        const Index I = fo + st.node[k];
        vm += (0.5 * st.w[k]) * (vs[I] + vn[I]);
      }
      finish_point(p, l, dt * vm, f_dt, bad, out);
      return;
    }
    finish_point(p, l, dt * vg, f_dt, bad, out);
  }, pw);
  if constexpr (Usavg) {
    if (has_trac) {
      // Tractions are spread from their surface points (particles_to_grid); serial, few points.
      Stencil<Dim> st;
      for (const PointLoads::SurfaceForce& sf : loads_.surface_forces()) {
        if (sf.index < begin || (end >= 0 && sf.index >= end)) continue;  // another range's point
        surface_point_stencil<Dim, K, G>(g, spline_faces_, sf.point, st);
        const Index fo = field_offset(sf.index);
        Vec3 vm;
        for (int k = 0; k < st.count; ++k) vm += (0.5 * st.w[k]) * (vs[fo + st.node[k]] + vn[fo + st.node[k]]);
        pw[0] += dot(sf.force, vm);
      }
    }
  }
  comm_.sum(pw, 2);
  external_work_ += dt * pw[0];
  transfer_work_ += pw[1];
  first_bad_ = bad.load();
  first_out_ = out.load();
}

#pragma GCC diagnostic pop

template <int Dim, ShapeKind K, bool G>
void MpmSolver::slow_grid_to_particles(double dt, int substeps, Index begin, Index end) {
  // Multi-rate stepping: the slow points' USAVG update at the end of their step, from the grid
  // share they held over its substeps (MultirateGrid, mpm_multirate.cpp). They have not moved
  // since the step began, so their weights are those their sums were mapped with. Where no fast
  // point shares a node, the substeps' velocities are one USAVG step's (constant force): u - u0
  // = dt a, disp = dt (v_n + v_end) / 2 and w = v_end, so the update below is grid_to_particles's.
  //   velocity: FLIP v + S (u - u0), PIC S v_end (the node's last velocity), blended with the
  //   PIC share of as many steps as the substeps, 1 - flip^substeps: the PIC share damps what
  //   the grid cannot carry at (1 - flip) per step, and a slow point is damped as much per unit
  //   time as if it had taken every substep; with patches, every substep's share scaled as
  //   grid_to_particles scales it for a point in coarser cells than the step's, so that a slow
  //   point is damped as in a run of one step for all;
  //   position: x + S disp, disp the nodes' path over the substeps;
  //   second stress half: L from w = 2 disp / dt - v_n over dt / 2, so that the two halves'
  //   strain, dt/2 (L(v_n) + L(w)) = L(disp), is the one the positions took (USAVG's consistency).
  const GridGeometry& g = grid_.geom;
  auto* v = points_.view(kVelocity);
  const auto* half = points_.view(kHalfSize);
  const auto* mass = points_.real(kMass);
  const Vec3* u = multirate_.u.data();
  const Vec3* u0 = multirate_.u0.data();
  const Vec3* disp = multirate_.disp.data();
  const Vec3* w = multirate_.vn0.data();  // holds w (step_multirate)
  const Vec3* vend = grid_.velocity_new.data();
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  const bool has_ext = !multirate_.fext.empty();
  const bool by_cell = G && pic_by_cell();
  const double steps_flip = std::pow(flip_, substeps);
  const Index n = points_.size();
  std::atomic<Index> bad{n}, out{n};
  double pw[2];
  deterministic_sum<2>(begin, end, [&](Index p, double* o) {
    Stencil<Dim> st;
    const Vec3 xp = x_[p];
    point_stencil<Dim, K, G>(p, xp, half[p], st);
    const Index fo = field_offset(p);
    const double flip =
        by_cell ? std::pow(1.0 - pic_share_by_cell(xp), substeps) : steps_flip;
    Vec3 du, upic, d;
    Mat3 l;
    for (int k = 0; k < st.count; ++k) {
      const Index I = fo + st.node[k];
      const double wk = st.w[k];
      du += wk * (u[I] - u0[I]);
      upic += wk * vend[I];
      d += wk * disp[I];
      const Vec3& dN = st.grad[k];
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j) l(i, j) += w[I][i] * dN[j];
    }
    if (axisym) {
      double rate, wr = 0.0;
      for (int k = 0; k < st.count; ++k) wr += st.w[k] * w[fo + st.node[k]][0];
      l(2, 2) = hoop_rate_near_axis<Dim, K>(g, xp, half[p], st, w + fo, rate) ? rate : wr / xp[0];
    }
    const Vec3 v_old = v[p];
    v[p] = flip * (v_old + du) + (1.0 - flip) * upic;
    // The point loads work over the nodes' path (USAVG books them at the grid's velocity).
    if (has_ext) o[0] += dot(multirate_.fext[static_cast<std::size_t>(p - begin)], d);
    o[1] += 0.5 * mass[p] * (dot(v[p], v[p]) - dot(v_old, v_old));
    finish_point(p, l, d, 0.5 * dt, bad, out);
  }, pw);
  // Their surface tractions, at their own points (serial: few).
  Stencil<Dim> st;
  for (const PointLoads::SurfaceForce& sf : multirate_.surface) {
    surface_point_stencil<Dim, K, G>(g, spline_faces_, sf.point, st);
    const Index fo = field_offset(sf.index);
    Vec3 d;
    for (int k = 0; k < st.count; ++k) d += st.w[k] * disp[fo + st.node[k]];
    pw[0] += dot(sf.force, d);
  }
  external_work_ += pw[0];
  transfer_work_ += pw[1];
  first_bad_ = bad.load();
  first_out_ = out.load();
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::velocity_gradient_from_grid(double dt, bool move, Index begin, Index end) {
  // L, F and the volume from the grid velocity in velocity_new, with the shape functions of this
  // step: for MUSL (Sulsky, Zhou & Schreyer, CPC 87 (1995) 236) the velocity the updated particle
  // momenta map back to, with the points moved by `displacement_`; for USAVG's first half the
  // constrained mapped velocity, the points left in place (`move` false).
  const GridGeometry& g = grid_.geom;
  const auto* half = points_.view(kHalfSize);
  const Vec3* vg = grid_.velocity_new.data();
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  const Index n = points_.size();
  if (end < 0) end = n;
  std::atomic<Index> bad{n}, out{n};
  if constexpr (K == ShapeKind::Linear && Dim == 3 && !G) {
    if (grid_.fields == 1) {
      // Eight points per vector (mpm/gradient_linear_3d.hpp): the loop below's sums to round-off.
      constexpr Index kChunk = kPointChunk;
      for_each_point_chunk((end - begin + kChunk - 1) / kChunk, [&](Index c) {
        const Index last = std::min(end, begin + (c + 1) * kChunk);
        Mat3 l[kGradientGroup];
        for (Index p0 = begin + c * kChunk; p0 < last; p0 += kGradientGroup) {
          const int m = static_cast<int>(std::min<Index>(kGradientGroup, last - p0));
          linear_3d_gradients(g, vg, x_ + p0, m, l);
          for (int j = 0; j < m; ++j) finish_point(p0 + j, l[j], move ? displacement_[p0 + j] : Vec3{}, dt, bad, out);
        }
      });
      first_bad_ = bad.load();
      first_out_ = out.load();
      return;
    }
  }
  for_each(begin, end, [&](Index p) {
    Stencil<Dim> st;
    const Vec3 xp = x_[p];
    point_stencil<Dim, K, G>(p, xp, half[p], st);
    const Index fo = field_offset(p);
    Mat3 l;
    double vr = 0.0;
    for (int k = 0; k < st.count; ++k) {
      const Vec3& u = vg[fo + st.node[k]];
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j) l(i, j) += u[i] * st.grad[k][j];
      vr += st.w[k] * u[0];
    }
    if (axisym) {
      double rate;
      l(2, 2) = hoop_rate_near_axis<Dim, K>(g, xp, half[p], st, vg + fo, rate) ? rate : vr / xp[0];
    }
    finish_point(p, l, move ? displacement_[p] : Vec3{}, dt, bad, out);
  });
  first_bad_ = bad.load();
  first_out_ = out.load();
}

void MpmSolver::handle_exits() {
  const Index n = points_.size();
  if (first_out_ >= n) return;
  if (scenario_.simulation.on_particle_exit != "delete")
    fail(first_out_, "left the grid box (set simulation.on_particle_exit: delete to remove such particles)");
  const auto* x = points_.view(kPosition);
  std::vector<char> keep(n, 1);
  for (Index p = 0; p < n; ++p)
    for (int a = 0; a < dim_; ++a)
      if (!(x[p][a] >= layout_.box_lower[a] && x[p][a] <= layout_.box_upper[a])) keep[p] = 0;
  pts_.remove(keep);
}

void MpmSolver::fail(Index p, const std::string& what) const { pts_.fail(p, what, steps_, time_); }

template <int Dim, ShapeKind K, bool G>
void MpmSolver::step_impl(double dt) {
  bind_fields();
  build_slabs();
  loads_.compute(scenario_, points_, time_);
  mark_active_blocks();
  // The first mapping computes each point's GIMP windows; the step's later passes reuse them.
  windows_current_ = false;
  if constexpr (K == ShapeKind::Gimp) gimp_windows_of_points<Dim>().resize(points_.size());
  if (!level_geom_.empty()) stencil_level_.resize(static_cast<std::size_t>(points_.size()));
  // USAVG's first half update reads the mass and momentum; the forces come from its stress (the
  // weights must not follow F within the step: p2g_part.hpp).
  particles_to_grid<Dim, K, G>(usavg_ ? P2gPart::Kinematics : P2gPart::All);
  windows_current_ = K == ShapeKind::Gimp;
  if (usavg_) {
    first_half_stress_update<Dim, K, G>(dt);
    particles_to_grid<Dim, K, G>(P2gPart::Forces);  // the forces of the half-updated stress
  }
  update_grid(dt);
  if (xpic_active()) xpic_velocity<Dim, K, G>(dt);
  if (usavg_) {
    grid_to_particles<Dim, K, G, true>(dt);
    transfer_work_ -= grid_kinetic_energy_change(dt);
  } else {
    grid_to_particles<Dim, K, G, false>(dt);
  }
  if (musl_) {
    // Map the updated particle momenta back with the same shape functions, then L from them.
    particles_to_grid<Dim, K, G>(P2gPart::Momentum);
    velocity_from_momentum();
    // Kinematics only (the particle velocities are final): the same constraints, nothing booked.
    apply_velocity_bcs(grid_.velocity_new.data());
    if (grid_.fields > 1) {
      apply_contact(grid_.velocity_new.data(), false);
      apply_velocity_bcs(grid_.velocity_new.data());
    }
    if (!patch_.empty()) fill_patch_nodes(grid_.velocity_new.data());
    if (!mirror_faces_.empty()) fill_mirror_ghosts(grid_.velocity_new.data());
    velocity_gradient_from_grid<Dim, K, G>(dt, true);
  }
  windows_current_ = false;  // the points have moved
  // The step's kinematics are done: count it, so that failure messages, outputs and statistics
  // name the step whose state they show.
  time_ += dt;
  ++steps_;
  if (const std::int64_t d = frozen_discarded_.exchange(0)) pts_.add_frozen_increments_discarded(d);
  if (first_bad_ < points_.size())
    fail(first_bad_, "inverted or non-finite deformation gradient (J <= 0, NaN or infinite)");
  const double sdt = usavg_ ? 0.5 * dt : dt;  // USAVG: the second half
  if (anti_locking_ == AntiLocking::FBar)  // volumetric increment averaged per cell (anti_locking.hpp)
    fbar_.apply(grid_.geom, dimension_, sdt, fbar_points(), fbar_across_ranks());
  pts_.update_stress(sdt, steps_, time_);
  if (bulk_viscosity_.active()) bulk_viscosity_pass(sdt, false);
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::step_any(double dt) {
  // Multi-rate: as many substeps as the fastest point's step needs (stable_dt chose dt).
  const int substeps = multirate_max_ > 1 && fine_dt_ > 0.0
                           ? std::max(1, static_cast<int>(std::ceil(dt / fine_dt_ * (1.0 - 1e-12))))
                           : 1;
  if (substeps > 1) step_multirate<Dim, K, G>(dt, substeps);
  else step_impl<Dim, K, G>(dt);
  if (!idle_ids_.empty()) check_idle_points_rest();
}

void MpmSolver::bulk_viscosity_pass(double dt, bool book_new, Index begin, Index end) {
  if (grid_.geom.graded) update_cell_lengths(begin, end);  // the viscous length is each point's cell
  const BulkViscosityPass r = apply_bulk_viscosity(pts_, bulk_viscosity_, grid_.geom.h, dt, book_new, wave_scratch_,
                                                   reference_wave_scratch_,
                                                   grid_.geom.graded ? cell_length_.data() : nullptr, begin, end);
  // This rank's share only: a collective here would not match a rank that failed in the step
  // (rethrow_agreed); energies() and save_state() sum it.
  viscous_work_ += r.work;
  viscous_speed_ = r.signal_speed;  // stable_dt takes the maximum over the ranks
  viscous_rate_ = r.signal_rate;
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::first_half_stress_update(double dt) {
  // USAVG (Nairn, CMES 4 (2003) 649): the stress takes half its increment from the mapped grid
  // velocity v_n before the forces are computed, and the other half from v_{n+1} after the grid
  // update. Within the step this is position Verlet, x_{n+1/2} = x_n + dt/2 v_n, v_{n+1} = v_n +
  // dt a(x_{n+1/2}), x_{n+1} = x_{n+1/2} + dt/2 v_{n+1}: symplectic, where USL (x_{n+1} = x_n + dt
  // v_{n+1}) is symplectic Euler and MUSL's remapped velocity, nearly the next step's v_n, makes
  // it update-stress-first-like (for a linear oscillator the amplification matrix of USF has
  // determinant 1 + k dt^2: energy grows). Over many steps all three are first order in time,
  // since each step starts from the velocity mapped from the particles, not from the grid's
  // updated one (MpmSolver.TemporalOrderOfTheUpdateSchemes). The particles' velocities do not
  // change here; they receive the constraints' impulses with the grid update (update_grid).
  usavg_start_velocity();
  first_half_points<Dim, K, G>(dt, 0, points_.size());
}

void MpmSolver::usavg_start_velocity() {
  const bool multi = grid_.fields > 1;
  const Index nall = grid_.geom.node_count() * grid_.fields;
  usavg_start_.resize(nall);
  if (multi) {
    grid_.impulse.resize(nall);
    grid_.friction_impulse.resize(nall);
  }
  for_each_active_node([&](Index i) {
    const double m = grid_.mass[i];
    grid_.accel[i] = m > kTinyMass ? (1.0 / m) * grid_.velocity[i] : Vec3{};  // v0, scratch
    usavg_start_[i] = grid_.accel[i];
    if (multi) grid_.impulse[i] = grid_.friction_impulse[i] = Vec3{};
  });
  // Contact, then the conditions, on v0 (booked with (v0 + v_n) / 2); update_grid goes on from
  // this v_n.
  apply_contact(usavg_start_.data(), true);
  boundary_impulses_.clear();
  apply_velocity_bcs(usavg_start_.data(), &boundary_impulses_);
  book_impulses(grid_.accel.data(), usavg_start_.data());
  if (!patch_.empty()) fill_patch_nodes(usavg_start_.data());  // hanging nodes: G2P reads them too
  if (!mirror_faces_.empty()) fill_mirror_ghosts(usavg_start_.data());  // G2P reads it there too
  for_each_active_node([&](Index i) { grid_.velocity_new[i] = usavg_start_[i]; });
  if (!patch_.empty()) fill_patch_nodes(grid_.velocity_new.data());
  if (!mirror_faces_.empty()) fill_mirror_ghosts(grid_.velocity_new.data());
}

template <int Dim, ShapeKind K, bool G>
void MpmSolver::first_half_points(double dt, Index begin, Index end) {
  velocity_gradient_from_grid<Dim, K, G>(0.5 * dt, false, begin, end);
  if (first_bad_ < points_.size())  // named as the step it happens in (steps_ counts completed ones)
    pts_.fail(first_bad_,
              "inverted or non-finite deformation gradient (J <= 0, NaN or infinite) in the first half of the step",
              steps_ + 1, time_);
  if (anti_locking_ == AntiLocking::FBar)
    fbar_.apply(grid_.geom, dimension_, 0.5 * dt, fbar_points(), fbar_across_ranks());
  pts_.update_stress(0.5 * dt, steps_, time_, {}, begin, end);
  if (bulk_viscosity_.active()) bulk_viscosity_pass(0.5 * dt, true, begin, end);  // the q the step's forces use
}

FBarPoints MpmSolver::fbar_points() {
  return {points_.size(), x_, L_, F_, vol_, vol0_, points_.ints(kMaterialIndex),
          static_cast<int>(pts_.materials().size())};
}

FBarSlotSum MpmSolver::fbar_across_ranks() {
  if (!comm_.distributed()) return {};
  // The (cell, material) sums are node arrays of `materials` components: the blocks shared with
  // other ranks are summed like the P2G's (mark_active_blocks widens the blocks by a cell so that
  // a point's cell after the position update lies in them).
  return [this](double* a, double* b, int materials) {
    exchange_.sum(comm_, {{a, materials}, {b, materials}}, 1);
  };
}

void MpmSolver::bind_fields() {
  x_ = points_.view(kPosition);
  F_ = points_.view(kDeformationGradient);
  L_ = points_.view(kVelocityGradient);
  vol_ = points_.real(kVolume);
  vol0_ = points_.real(kReferenceVolume);
  body_ = points_.ints(kBodyIndex);
}

void MpmSolver::step(double dt) {
  if (!comm_.distributed()) {
    step_local(dt);
    return;
  }
  // A failure on one rank stops every rank with the same diagnostic. Nothing after the first
  // place a rank can throw (the kinematics check) waits for the other ranks.
  run_agreed(comm_, [&] { step_local(dt); });
}

void MpmSolver::step_local(double dt) {
  if (comm_.distributed()) redistribute();
  activate_pending();
  if (sort_every_ > 0 && steps_ % sort_every_ == 0) sort_by_cell();
  const bool three = dim_ == 3;
  if (grid_.geom.graded) {  // no cubic B-spline on a graded grid (refused in the constructor)
    switch (shape_) {
      case ShapeKind::Linear:
        three ? step_any<3, ShapeKind::Linear, true>(dt) : step_any<2, ShapeKind::Linear, true>(dt);
        break;
      case ShapeKind::Gimp:
        three ? step_any<3, ShapeKind::Gimp, true>(dt) : step_any<2, ShapeKind::Gimp, true>(dt);
        break;
      case ShapeKind::Cpdi:
        three ? step_any<3, ShapeKind::Cpdi, true>(dt) : step_any<2, ShapeKind::Cpdi, true>(dt);
        break;
      case ShapeKind::BSpline3: break;
    }
  } else {
    switch (shape_) {
      case ShapeKind::Linear:
        three ? step_any<3, ShapeKind::Linear, false>(dt) : step_any<2, ShapeKind::Linear, false>(dt);
        break;
      case ShapeKind::Gimp:
        three ? step_any<3, ShapeKind::Gimp, false>(dt) : step_any<2, ShapeKind::Gimp, false>(dt);
        break;
      case ShapeKind::Cpdi:
        three ? step_any<3, ShapeKind::Cpdi, false>(dt) : step_any<2, ShapeKind::Cpdi, false>(dt);
        break;
      case ShapeKind::BSpline3:
        three ? step_any<3, ShapeKind::BSpline3, false>(dt) : step_any<2, ShapeKind::BSpline3, false>(dt);
        break;
    }
  }
  handle_exits();
}

std::vector<double> MpmSolver::history_values() const {
  std::vector<double> v = loads_.history_values(scenario_);  // indenter reactions: sums over particles
  comm_.sum(v.data(), static_cast<int>(v.size()));
  return v;
}

std::vector<std::pair<std::string, double>> MpmSolver::result_values() const {
  // Particles whose F was remapped at mpm.distortion_limit (absent: none).
  const std::int64_t remaps = pts_.distortion_remaps();
  std::vector<std::pair<std::string, double>> out;
  if (remaps > 0) out.emplace_back("distortion_remaps", static_cast<double>(remaps));
  // Inverting increments of stress-free eroded points, discarded (finish_point; absent: none).
  const std::int64_t frozen = pts_.frozen_increments_discarded();
  if (frozen > 0) out.emplace_back("frozen_increments_discarded", static_cast<double>(frozen));
  if (multirate_tally_.steps > 0.0) {
    // Multi-rate stepping (one rank): its steps, their substeps, and the point updates one step
    // for all at the substeps' length would have made over those it made.
    const MultirateTally& t = multirate_tally_;
    out.emplace_back("multirate_steps", t.steps);
    out.emplace_back("multirate_substeps", t.substeps);
    const double made = t.fast_point_steps + t.slow_point_steps;
    if (made > 0.0) out.emplace_back("multirate_update_ratio", t.single_rate_point_steps / made);
  }
  if (!comm_.distributed()) return out;
  const double steps = std::max(halo_steps_, 1.0);
  const double n = static_cast<double>(points_.size());
  out.insert(out.end(), {{"ranks", static_cast<double>(comm_.size())},
          {"fewest_particles_on_a_rank", comm_.min(n)},  // collective: every rank reports
          {"most_particles_on_a_rank", comm_.max(n)},
          {"repartitions", static_cast<double>(repartitions_)},
          {"particles_migrated", migrated_},
          {"max_particle_imbalance", max_imbalance_},
          // This rank's halo (rank 0's in the summary): the scaling model's measured input.
          {"halo_bytes_per_step_rank0", halo_bytes_ / steps},
          {"halo_messages_per_step_rank0", halo_messages_ / steps},
          // Ranks rank 0 exchanged its block list with (mean over the steps that used the
          // neighbour exchange; the others went to every rank).
          {"neighbour_ranks_rank0", neighbour_plans_ > 0 ? neighbour_sum_ / neighbour_plans_ : 0.0}});
  return out;
}

EnergyTotals MpmSolver::energies() const {
  const double k = reporting_scale();
  EnergyTotals e = pts_.energies(k, external_work_);
  e.damping = k * damping_work_;
  e.contact = k * contact_work_;
  e.friction = k * friction_work_;
  e.transfer = k * transfer_work_;
  e.boundary = k * boundary_work_;
  e.viscous = k * comm_.sum(viscous_work_);
  return e;
}

namespace {

std::unique_ptr<Solver> make_mpm(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials,
                                 const Communicator& comm) {
  return std::make_unique<MpmSolver>(sc, std::move(materials), comm);
}

}  // namespace

// What the multi-rate step (mpm_multirate.cpp) calls from here.
#define BALLISTA_MULTIRATE_PARTS(Dim, K, G)                                                   \
  template void MpmSolver::particles_to_grid<Dim, K, G>(P2gPart, const Vec3*, Index, Index);  \
  template void MpmSolver::grid_to_particles<Dim, K, G, true>(double, Index, Index);          \
  template void MpmSolver::first_half_points<Dim, K, G>(double, Index, Index);                \
  template void MpmSolver::slow_grid_to_particles<Dim, K, G>(double, int, Index, Index);         \
  template void MpmSolver::step_impl<Dim, K, G>(double);
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::Linear, false)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::Linear, false)
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::Gimp, false)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::Gimp, false)
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::Cpdi, false)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::Cpdi, false)
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::BSpline3, false)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::BSpline3, false)
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::Linear, true)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::Linear, true)
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::Gimp, true)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::Gimp, true)
BALLISTA_MULTIRATE_PARTS(2, ShapeKind::Cpdi, true)
BALLISTA_MULTIRATE_PARTS(3, ShapeKind::Cpdi, true)
#undef BALLISTA_MULTIRATE_PARTS

}  // namespace ballista

BALLISTA_REGISTER_SOLVER(ballista::SolverFactory{
    .name = "mpm",
    .description = "explicit material point method (Sulsky et al. 1994; USL / modified USL, FLIP/PIC blend; thesis "
                   "seed 000)",
    .dimensions = {"3d", "plane_strain", "axisymmetric"},
    .section = "mpm",
    .params = ballista::mpm_params(),
    .create = &ballista::make_mpm,
    .distributed = true,
    .graded_grid = true,
    .cut_lattice = true,
    .velocity_fields = true,
    .courant_step = true})
