#include "mpm/mpm_solver.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "analysis/mms_axis_aligned.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/system_memory.hpp"
#include "geometry/seeding.hpp"

namespace ballista {

namespace {

constexpr double kTinyMass = 1e-200;  // nodes lighter than this carry no material

int axis_count(Dimension d) { return d == Dimension::ThreeD ? 3 : 2; }

/// Records the smallest offending index seen by any thread (deterministic for any thread count).
void record_min(std::atomic<Index>& slot, Index p) {
  Index cur = slot.load(std::memory_order_relaxed);
  while (p < cur && !slot.compare_exchange_weak(cur, p, std::memory_order_relaxed)) {
  }
}

template <int Dim, ShapeKind K>
inline void stencil_of(const GridGeometry& g, const Vec3& x, const Vec3& half, const Mat3& F,
                       Stencil<Dim>& s) {
  if constexpr (K == ShapeKind::Linear) {
    linear_stencil<Dim>(g, x, s);
  } else if constexpr (K == ShapeKind::Gimp) {
    gimp_stencil<Dim>(g, x, half, s);  // uGIMP: reference half-size (Bardenhagen & Kober 2004)
  } else if constexpr (K == ShapeKind::BSpline3) {
    bspline3_stencil<Dim>(g, x, s);
  } else {
    // CPDI1 domain vectors r_j = F (half_j e_j) (Sadeghirad et al. 2011, eq. 11).
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r(i, j) = F(i, j) * half[j];
    cpdi_stencil<Dim>(g, x, r, s);
  }
}

}  // namespace

void MpmSolver::check_memory(const Scenario& sc, double nodes) const {
  // Refuse a run that cannot fit before allocating it (issue 11). Per node: mass and four Vec3
  // arrays of GridNodes. Per point: every declared field, plus the solver's per-point scratch
  // (external and traction forces, MUSL displacement: 3 Vec3; slab and sort indices: ~5 words).
  // The point count is the bodies' bounding-box lattice, an upper bound.
  constexpr double kBytesPerNode = sizeof(double) + 4 * sizeof(Vec3);
  const double bytes_per_point = points_.bytes_per_point() + 3 * sizeof(Vec3) + 5 * sizeof(Index);
  double points = 0.0;
  for (const auto& body : sc.bodies) points += lattice_point_bound(body, sc.grid, dimension_);
  const double needed = nodes * kBytesPerNode + points * bytes_per_point;
  require_memory(needed,
                 fmt::format("{:.3g} grid nodes x {:g} B + up to {:.3g} points x {:g} B", nodes, kBytesPerNode, points,
                             bytes_per_point),
                 sc.file, "grid.cell_size");
}

MpmSolver::MpmSolver(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials,
                     Communicator comm)
    : scenario_(sc), materials_(std::move(materials)), comm_(comm) {
  dimension_ = sc.simulation.dimension;
  dim_ = axis_count(dimension_);
  shape_ = parse_shape_kind(sc.mpm.shape_function);
  musl_ = sc.mpm.update == "musl";
  flip_ = sc.mpm.flip;
  damping_ = sc.simulation.damping;

  // Grid block: the physical box plus ghost node layers so every stencil stays in the block.
  const double h = sc.grid.cell_size;
  GridGeometry& g = grid_.geom;
  g.h = h;
  g.dim = dim_;
  for (int a = 0; a < 3; ++a) {
    if (a < dim_) {
      const int cells = static_cast<int>(std::ceil((sc.grid.upper[a] - sc.grid.lower[a]) / h - 1e-9));
      box_lower_[a] = sc.grid.lower[a];
      box_upper_[a] = sc.grid.lower[a] + cells * h;
      g.origin[a] = sc.grid.lower[a] - ghost_ * h;
      g.nodes[a] = cells + 1 + 2 * ghost_;
      box_first_[a] = ghost_;
      box_last_[a] = ghost_ + cells;
    } else {
      box_lower_[a] = box_upper_[a] = g.origin[a] = 0.0;
      g.nodes[a] = 1;
      box_first_[a] = box_last_[a] = 0;
    }
  }
  slab_axis_ = dim_ - 1;

  // Points: common fields, every material's state fields, then the bodies.
  declare_point_fields(points_);
  for (const auto& m : materials_) m->declare_fields(points_);
  check_memory(sc, static_cast<double>(g.node_count()));
  grid_.resize(g.node_count());
  std::int64_t next_id = 0;
  std::vector<double> activation;
  std::vector<int> activation_stage;
  for (size_t b = 0; b < sc.bodies.size(); ++b) {
    const BodySpec& body = sc.bodies[b];
    int mi = -1;
    for (size_t m = 0; m < materials_.size(); ++m)
      if (materials_[m]->name() == body.material) mi = static_cast<int>(m);
    if (mi < 0)
      throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path + ".material",
                      "unknown material '" + body.material + "'");
    const Index n0 = points_.size();
    if (body.segments.empty()) {
      seed_body(body, static_cast<int>(b), mi, *materials_[mi], sc.grid, dimension_, points_, next_id);
      activation.resize(points_.size(), body.activation_time);
    } else {
      // Rods and jets: each segment with its own shape, velocity and activation time.
      for (size_t k = 0; k < body.segments.size(); ++k) {
        BodySpec piece = body;
        piece.shape = body.segments[k].shape;
        piece.velocity = body.segments[k].velocity;
        const Index s0 = points_.size();
        seed_body(piece, static_cast<int>(b), mi, *materials_[mi], sc.grid, dimension_, points_, next_id);
        auto* seg = points_.ints("segment");
        for (Index p = s0; p < points_.size(); ++p) seg[p] = static_cast<int>(k);
        activation.resize(points_.size(), body.segments[k].activation_time);
      }
    }
    activation_stage.resize(points_.size(), body.activation_stage);
    materials_[mi]->initialise_state(points_, n0, points_.size());
    if (body.initial_state == "mms_axis_aligned") {
      // Start on the manufactured solution at t = 0 (CATALOGUE B1): velocity, F and stress.
      const mms::AxisAligned mms;
      auto* x0 = points_.view<Vec3>("x0");
      auto* v = points_.view<Vec3>("v");
      auto* F = points_.view<Mat3>("F");
      auto* R = points_.view<Mat3>("R");
      auto* stress = points_.view<Mat3>("stress");
      auto* vol = points_.real("volume");
      const auto* vol0 = points_.real("volume0");
      auto* x = points_.view<Vec3>("x");
      for (Index p = n0; p < points_.size(); ++p) {
        // The lattice is the reference configuration X; the body starts displaced by u(X, 0).
        x[p] = x0[p] + mms.displacement(x0[p], 0.0);
        v[p] = mms.velocity(x0[p], 0.0);
        F[p] = mms.F(x0[p], 0.0);
        R[p] = Mat3::identity();  // F is diagonal and positive: no rotation
        stress[p] = materials_[mi]->initial_stress(F[p]);
        vol[p] = vol0[p] * det(F[p]);
      }
    }
  }
  for (size_t k = 0; k < sc.loads.size(); ++k) {
    const LoadSpec& load = sc.loads[k];
    if (load.type != "pressure") continue;
    const int bi = body_index(sc, load.body);
    const Index marked = mark_pressure_surface(load, static_cast<int>(k), sc.bodies.at(bi), bi, h,
                                               dimension_, points_);
    if (marked == 0)
      throw DeckError(load.mark.file, load.mark.line, load.mark.column, load.mark.key_path + ".surface",
                      "no particle of body '" + load.body + "' lies on surface '" + load.surface + "'");
    load_area_fields_.push_back("load_area_" + std::to_string(k));
  }
  // Bodies with a later activation time wait in pending_.
  std::vector<Index> later;
  std::vector<char> keep(points_.size(), 1);
  stage_start_.assign(sc.stages.size() + 1, std::numeric_limits<double>::infinity());
  stage_start_[0] = 0.0;
  for (Index p = 0; p < points_.size(); ++p)
    if (activation[p] > 0.0 || activation_stage[p] > 0) {
      later.push_back(p);
      keep[p] = 0;
      pending_activation_.push_back(activation[p]);
      pending_stage_.push_back(activation_stage[p]);
    }
  pending_ = points_.empty_like();
  if (!later.empty()) {
    pending_.append_from(points_, later);
    points_.compact(keep);
  }
  sort_by_cell();
}

void MpmSolver::begin_stage(int stage, double damping) {
  if (stage < 0 || stage >= static_cast<int>(stage_start_.size()))
    throw Error("stage index " + std::to_string(stage) + " out of range");
  stage_start_[stage] = time_;
  damping_ = damping;
}

double MpmSolver::reporting_scale() const {
  return dimension_ == Dimension::Axisymmetric ? 2.0 * std::numbers::pi : 1.0;
}

double MpmSolver::stable_dt() {
  // dt = CFL h / max_p (c_p + |v_p|)  (Courant condition with the dilatational wave speed).
  ensure_material_groups();
  double local_max = 0.0;
  for (size_t m = 0; m < materials_.size(); ++m)
    local_max = std::max(local_max, materials_[m]->max_signal_speed(
                                        points_, material_points_[m].data(),
                                        static_cast<Index>(material_points_[m].size())));
  const double speed = comm_.max(local_max);
  double dt = speed > 0.0 ? scenario_.simulation.cfl * grid_.geom.h / speed
                          : scenario_.simulation.end_time;
  if (scenario_.simulation.max_dt > 0.0) dt = std::min(dt, scenario_.simulation.max_dt);
  return dt;
}

StepLimiter MpmSolver::step_limiter() const {
  // Serial and per point through the virtual wave_speed: only for diagnostics (the run loop
  // calls it when the stable step reaches a new low).
  StepLimiter out;
  const auto* id = points_.ints("id");
  const auto* bid = points_.ints("body");
  const auto* mat = points_.ints("material");
  const auto* v = points_.view<Vec3>("v");
  const auto* F = points_.view<Mat3>("F");
  double best = -1.0;
  for (Index p = 0; p < points_.size(); ++p) {
    const double J = det(F[p]);
    const double c = materials_[mat[p]]->wave_speed(points_, p, J);
    const double s = norm(v[p]);
    if (c + s > best) {
      best = c + s;
      out = {id[p], static_cast<int>(bid[p]), c, s, J};
    }
  }
  return out;
}

void MpmSolver::ensure_material_groups() {
  if (!groups_dirty_) return;
  material_points_.resize(materials_.size());
  for (auto& list : material_points_) list.clear();  // keeps capacity: no allocation per sort
  const auto* mat = points_.ints("material");
  for (Index p = 0; p < points_.size(); ++p) material_points_[mat[p]].push_back(p);
  groups_dirty_ = false;
}

void MpmSolver::activate_pending() {
  if (pending_.size() == 0) return;
  std::vector<Index> now;
  std::vector<char> keep(pending_.size(), 1);
  std::vector<double> still;
  std::vector<int> still_stage;
  for (Index p = 0; p < pending_.size(); ++p) {
    // Activation times count from the start of the body's activation stage (infinite until then).
    if (stage_start_[pending_stage_[p]] + pending_activation_[p] <= time_) {
      now.push_back(p);
      keep[p] = 0;
    } else {
      still.push_back(pending_activation_[p]);
      still_stage.push_back(pending_stage_[p]);
    }
  }
  if (now.empty()) return;
  // Their kinetic and internal energy enters the energy balance as work done from outside (a
  // jet segment inserted at its velocity, thesis seed 000 §5.1), so the drift stays meaningful.
  {
    const auto* v = pending_.view<Vec3>("v");
    const auto* m = pending_.real("mass");
    const auto* e = pending_.real("internal_energy");
    for (Index p : now) inserted_energy_ += 0.5 * m[p] * dot(v[p], v[p]) + e[p];
  }
  points_.append_from(pending_, now);
  pending_.compact(keep);
  groups_dirty_ = true;
  pending_activation_.swap(still);
  pending_stage_.swap(still_stage);
  sort_by_cell();
}

void MpmSolver::sort_by_cell() {
  // Counting sort of points by cell, slab axis slowest, so that each slab's points are
  // contiguous and neighbouring points share grid nodes in cache.
  const Index n = points_.size();
  if (n == 0) return;
  const GridGeometry& g = grid_.geom;
  const auto* x = points_.view<Vec3>("x");
  std::vector<Index>& key = sort_key_;  // member scratch buffers: no allocation per sort
  key.resize(n);
  const Index ncell = g.node_count();
  for_each(0, n, [&](Index p) {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < dim_; ++a) c[a] = std::clamp(g.cell_of(x[p][a], a), 0, g.nodes[a] - 1);
    key[p] = g.node_index(c[0], c[1], c[2]);
  });
  std::vector<Index>& start = sort_start_;
  start.assign(ncell + 1, 0);
  for (Index p = 0; p < n; ++p) ++start[key[p] + 1];
  for (Index c = 0; c < ncell; ++c) start[c + 1] += start[c];
  std::vector<Index>& order = sort_order_;
  order.resize(n);
  for (Index p = 0; p < n; ++p) order[start[key[p]]++] = p;
  points_.permute(order);
  groups_dirty_ = true;
}

int MpmSolver::stencil_reach_now() const {
  if (shape_ != ShapeKind::Cpdi) return stencil_reach(shape_);
  // CPDI: the corners x_p +- r1 +- r2 +- r3 reach as far as the summed |r_j| components.
  const auto* F = points_.view<Mat3>("F");
  const auto* half = points_.view<Vec3>("half_size");
  const Index n = points_.size();
  double ext = 0.0;
#pragma omp parallel for reduction(max : ext) schedule(static) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p)
    for (int i = 0; i < dim_; ++i) {
      double e = 0.0;
      for (int j = 0; j < dim_; ++j) e += std::abs(F[p](i, j)) * half[p][j];
      ext = std::max(ext, e);
    }
  return stencil_reach(shape_, ext / grid_.geom.h);
}

void MpmSolver::build_slabs() {
  // Lock-free scatter: points are bucketed into slabs of slab_width_ cells along the slab axis.
  // Slabs two apart touch disjoint nodes when width >= 2 * reach, so even slabs are scattered in
  // parallel, then odd ones. Each node thus receives its contributions in an order fixed by the
  // point order alone, so the result does not depend on the thread count.
  const int reach = stencil_reach_now();
  if (reach + 1 > ghost_ && shape_ == ShapeKind::Cpdi) {
    // A CPDI domain larger than the ghost layers could reach outside the block.
    const auto* F = points_.view<Mat3>("F");
    Index worst = 0;
    double worst_norm = 0.0;
    for (Index p = 0; p < points_.size(); ++p)
      if (frobenius(F[p]) > worst_norm) { worst_norm = frobenius(F[p]); worst = p; }
    fail(worst, "CPDI particle domain spans more than " + std::to_string(ghost_) + " cells");
  }
  slab_width_ = std::max(2 * reach, 1);
  const GridGeometry& g = grid_.geom;
  const int nslab = (g.nodes[slab_axis_] + slab_width_ - 1) / slab_width_;
  const Index n = points_.size();
  const auto* x = points_.view<Vec3>("x");
  std::vector<int>& slab = slab_of_point_;  // member scratch: no allocation per step
  slab.resize(n);
  for_each(0, n, [&](Index p) {
    const int c = std::clamp(g.cell_of(x[p][slab_axis_], slab_axis_), 0, g.nodes[slab_axis_] - 1);
    slab[p] = c / slab_width_;
  });
  slab_start_.assign(nslab + 1, 0);
  for (Index p = 0; p < n; ++p) ++slab_start_[slab[p] + 1];
  for (int s = 0; s < nslab; ++s) slab_start_[s + 1] += slab_start_[s];
  slab_points_.resize(n);
  slab_fill_.assign(slab_start_.begin(), slab_start_.end() - 1);
  for (Index p = 0; p < n; ++p) slab_points_[slab_fill_[slab[p]]++] = p;
}

void MpmSolver::compute_external_forces() {
  const Index n = points_.size();
  if (scenario_.loads.empty()) {  // no loads: no external-force array, no external work
    fext_.clear();
    ftrac_.clear();
    surface_forces_.clear();
    return;
  }
  fext_.assign(n, Vec3{});
  ftrac_.clear();
  surface_forces_.clear();
  const auto* mass = points_.real("mass");
  const auto* bid = points_.ints("body");
  for (size_t k = 0; k < scenario_.loads.size(); ++k) {
    const LoadSpec& load = scenario_.loads[k];
    const double scale = load.curve.at(time_);
    const int body = body_index(scenario_, load.body);  // -1: every body
    if (load.type == "body_force") {
      const Vec3 acc = scale * load.acceleration;
      for_each(0, n, [&](Index p) {
        if (body < 0 || bid[p] == body) fext_[p] += mass[p] * acc;
      });
    } else if (load.type == "pressure") {
      // Traction -p n da on the current surface, n da = J F^-T N dA0 (Nanson's formula). It acts
      // at the particle's face on the surface, x_p + F (N o half), not at its centre: a force at
      // the centre puts part of the load on the node inside the boundary cell, whose stress then
      // equilibrates only (1 - w) of the traction (a quarter short with two particles per cell,
      // the surface-layer error of thesis seed 000 §5.1's particle point loads).
      const auto* F = points_.view<Mat3>("F");
      const auto* x = points_.view<Vec3>("x");
      const auto* half = points_.view<Vec3>("half_size");
      const auto* area = points_.view<Vec3>("load_area_" + std::to_string(k));
      const double pr = scale * load.pressure;
      if (ftrac_.size() != static_cast<size_t>(n)) ftrac_.assign(n, Vec3{});
      for (Index p = 0; p < n; ++p) {
        if (area[p][0] == 0.0 && area[p][1] == 0.0 && area[p][2] == 0.0) continue;
        const Vec3 f = (-pr) * (cofactor(F[p]) * area[p]);
        const double a = norm(area[p]);
        Vec3 offset;
        for (int i = 0; i < 3; ++i) offset[i] = area[p][i] / a * half[p][i];
        fext_[p] += f;
        ftrac_[p] += f;
        surface_forces_.push_back({x[p] + F[p] * offset, f});
      }
    } else if (load.type == "mms_axis_aligned") {
      const mms::AxisAligned mms;
      const auto* x0 = points_.view<Vec3>("x0");
      for_each(0, n, [&](Index p) {
        if (body < 0 || bid[p] == body) fext_[p] += mass[p] * mms.body_force(x0[p], time_);
      });
    }
  }
}

template <int Dim, ShapeKind K>
void MpmSolver::particles_to_grid(bool momentum_only) {
  const GridGeometry& g = grid_.geom;
  const auto* x = points_.view<Vec3>("x");
  const auto* v = points_.view<Vec3>("v");
  const auto* F = points_.view<Mat3>("F");
  const auto* half = points_.view<Vec3>("half_size");
  const auto* mass = points_.real("mass");
  const auto* vol = points_.real("volume");
  const auto* stress = points_.view<Mat3>("stress");
  double* gm = grid_.mass.data();
  Vec3* gp = grid_.velocity.data();
  Vec3* gf = grid_.force.data();
  const Index nn = g.node_count();
  for_each(0, nn, [&](Index i) {
    if (!momentum_only) { gm[i] = 0.0; gf[i] = Vec3{}; }
    gp[i] = Vec3{};
  });
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  const bool has_ext = !fext_.empty();
  const bool has_trac = !momentum_only && !ftrac_.empty();
  const int nslab = static_cast<int>(slab_start_.size()) - 1;
  if (has_trac) {
    // Tractions at the surface points, with the kernel's weights there (serial: few points).
    Stencil<Dim> st;
    for (const SurfaceForce& sf : surface_forces_) {
      if constexpr (K == ShapeKind::BSpline3) bspline3_stencil<Dim>(g, sf.point, st);
      else linear_stencil<Dim>(g, sf.point, st);
      for (int k = 0; k < st.count; ++k) gf[st.node[k]] += st.w[k] * sf.force;
    }
  }
  for (int color = 0; color < 2; ++color) {
#pragma omp parallel for schedule(dynamic, 1) if (points_.size() > kParallelThreshold)
    for (int s = color; s < nslab; s += 2) {
      Stencil<Dim> st;
      for (Index q = slab_start_[s]; q < slab_start_[s + 1]; ++q) {
        const Index p = slab_points_[q];
        stencil_of<Dim, K>(g, x[p], half[p], F[p], st);
        const double m = mass[p];
        const Vec3 mv = m * v[p];
        if (momentum_only) {
          for (int k = 0; k < st.count; ++k) gp[st.node[k]] += st.w[k] * mv;
          continue;
        }
        // f_I = -V_p sigma_p grad N_I + N_I f_ext,p (Sulsky et al. 1994, eq. 14); axisymmetric
        // adds the hoop term -V_p sigma_tt N_I / r_p to the radial force (per-radian volume).
        const Mat3 Vs = vol[p] * stress[p];
        const double hoop = axisym ? vol[p] * stress[p](2, 2) / x[p][0] : 0.0;
        // Surface tractions are spread from their own points below.
        const Vec3 fe = has_ext ? (has_trac ? fext_[p] - ftrac_[p] : fext_[p]) : Vec3{};
        for (int k = 0; k < st.count; ++k) {
          const Index I = st.node[k];
          const double w = st.w[k];
          const Vec3& dN = st.grad[k];
          gm[I] += w * m;
          gp[I] += w * mv;
          Vec3 f;
          for (int i = 0; i < 3; ++i)
            f[i] = w * fe[i] - (Vs(i, 0) * dN[0] + Vs(i, 1) * dN[1] + Vs(i, 2) * dN[2]);
          f[0] -= hoop * w;
          gf[I] += f;
        }
      }
    }
  }
}

void MpmSolver::apply_velocity_bcs(std::vector<Vec3>& vel) {
  const GridGeometry& g = grid_.geom;
  if (dimension_ == Dimension::Axisymmetric && box_lower_[0] == 0.0) {
    // The symmetry axis: radial velocity is zero on it (and on the ghost nodes beyond it) whatever
    // the x_min condition says; without this the hoop rate v_r / r of the particles next to the
    // axis is unbounded.
    for (int i = 0; i <= box_first_[0]; ++i)
      for (int j = 0; j < g.nodes[1]; ++j) vel[g.node_index(i, j, 0)][0] = 0.0;
  }
  for (int a = 0; a < dim_; ++a) {
    for (int side = 0; side < 2; ++side) {
      const FaceBC bc = scenario_.grid.faces[2 * a + side];
      if (bc == FaceBC::Free) continue;
      // Nodes on the face and the ghost layers beyond it.
      const int lo = side == 0 ? 0 : box_last_[a];
      const int hi = side == 0 ? box_first_[a] : g.nodes[a] - 1;
      const int b1 = (a + 1) % 3, b2 = (a + 2) % 3;
      for (int i = lo; i <= hi; ++i)
        for (int j = 0; j < g.nodes[b1]; ++j)
          for (int k = 0; k < g.nodes[b2]; ++k) {
            int ijk[3];
            ijk[a] = i; ijk[b1] = j; ijk[b2] = k;
            Vec3& u = vel[g.node_index(ijk[0], ijk[1], ijk[2])];
            switch (bc) {
              case FaceBC::Fixed: u = Vec3{}; break;
              case FaceBC::Symmetry: u[a] = 0.0; break;
              case FaceBC::Wall:  // rigid frictionless wall: no velocity into the wall, separation allowed
                if (side == 0) u[a] = std::max(u[a], 0.0); else u[a] = std::min(u[a], 0.0);
                break;
              case FaceBC::Free: break;
            }
          }
    }
  }
}

void MpmSolver::update_grid(double dt) {
  // v_I = p_I / m_I; a_I = f_I / m_I - c v_I (damping, thesis seed 000 eq. 5.1); explicit Euler.
  const Index nn = grid_.geom.node_count();
  for_each(0, nn, [&](Index i) {
    const double m = grid_.mass[i];
    if (m > kTinyMass) {
      const Vec3 v = (1.0 / m) * grid_.velocity[i];
      grid_.velocity[i] = v;
      const Vec3 a = (1.0 / m) * grid_.force[i] - damping_ * v;
      grid_.velocity_new[i] = v + dt * a;
    } else {
      grid_.velocity[i] = Vec3{};
      grid_.velocity_new[i] = Vec3{};
    }
  });
  apply_velocity_bcs(grid_.velocity_new);
  // The acceleration handed to the particles is the constrained change of velocity.
  for_each(0, nn, [&](Index i) {
    grid_.accel[i] = (1.0 / dt) * (grid_.velocity_new[i] - grid_.velocity[i]);
  });
  if (damping_ > 0.0) {
    // Work of the damping force -c m v over the step (midpoint velocity), booked as external work
    // so that the energy balance of a damped run still closes.
    double w[1];
    deterministic_sum<1>(0, nn, [&](Index i, double* o) {
      const double m = grid_.mass[i];
      if (m > kTinyMass)
        o[0] -= damping_ * m * dot(grid_.velocity[i], 0.5 * (grid_.velocity[i] + grid_.velocity_new[i]));
    }, w);
    external_work_ += dt * comm_.sum(w[0]);
  }
}

inline void MpmSolver::finish_point(Index p, const Mat3& l, const Vec3& disp, double dt,
                                    std::atomic<Index>& bad, std::atomic<Index>& out) {
  L_[p] = l;
  Vec3& x = x_[p];
  x += disp;
  // F_{n+1} = (I + dt L) F_n (thesis seed 000 eq. 4.9); volume from J = det F.
  Mat3& F = F_[p];
  F = (Mat3::identity() + dt * l) * F;
  const double J = det(F);
  vol_[p] = vol0_[p] * J;
  if (!(J > 0.0) || !all_finite(F)) record_min(bad, p);
  for (int a = 0; a < dim_; ++a)
    if (!(x[a] >= box_lower_[a] && x[a] <= box_upper_[a])) record_min(out, p);
}

template <int Dim, ShapeKind K>
void MpmSolver::grid_to_particles(double dt) {
  // One pass per point: grid velocity, acceleration and velocity gradient at the point; FLIP/PIC
  // velocity update; position, F and volume update (USL); failure and exit detection.
  const GridGeometry& g = grid_.geom;
  auto* v = points_.view<Vec3>("v");
  const auto* half = points_.view<Vec3>("half_size");
  const Vec3* vn = grid_.velocity_new.data();
  const Vec3* ga = grid_.accel.data();
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  const bool has_ext = !fext_.empty();
  const bool defer = musl_;  // MUSL: L, F and positions after the second projection
  const double flip = flip_;
  const Index n = points_.size();
  if (defer) displacement_.resize(n);
  std::atomic<Index> bad{n}, out{n};
  double pw[1];
  deterministic_sum<1>(0, n, [&](Index p, double* o) {
    Stencil<Dim> st;
    const Vec3 xp = x_[p];
    stencil_of<Dim, K>(g, xp, half[p], F_[p], st);
    Vec3 vg, acc;
    Mat3 l;
    for (int k = 0; k < st.count; ++k) {
      const Vec3& u = vn[st.node[k]];
      const double w = st.w[k];
      vg += w * u;
      acc += w * ga[st.node[k]];
      const Vec3& dN = st.grad[k];
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j) l(i, j) += u[i] * dN[j];
    }
    // Axisymmetric hoop rate v_r / r (thesis seed 000 ch. 5: Uintah's axisymmetric MPM).
    if (axisym) l(2, 2) = vg[0] / xp[0];
    const Vec3 v_old = v[p];
    // FLIP/PIC blend: flip (v + dt a) + (1 - flip) v_grid (Brackbill & Ruppel 1986 FLIP).
    v[p] = flip * (v_old + dt * acc) + (1.0 - flip) * vg;
    if (has_ext) o[0] += dot(fext_[p], 0.5 * (v_old + v[p]));
    // Positions move with the grid velocity (x += dt sum N_I v_I).
    if (defer) {
      displacement_[p] = dt * vg;
      return;
    }
    finish_point(p, l, dt * vg, dt, bad, out);
  }, pw);
  external_work_ += dt * comm_.sum(pw[0]);
  first_bad_ = bad.load();
  first_out_ = out.load();
}

template <int Dim, ShapeKind K>
void MpmSolver::velocity_gradient_from_grid(double dt) {
  // Modified USL (Sulsky, Zhou & Schreyer, CPC 87 (1995) 236): L from the grid velocity that the
  // updated particle momenta map back to, with the shape functions of this step.
  const GridGeometry& g = grid_.geom;
  const auto* half = points_.view<Vec3>("half_size");
  const Vec3* vg = grid_.velocity_new.data();
  const bool axisym = dimension_ == Dimension::Axisymmetric;
  const Index n = points_.size();
  std::atomic<Index> bad{n}, out{n};
  for_each(0, n, [&](Index p) {
    Stencil<Dim> st;
    const Vec3 xp = x_[p];
    stencil_of<Dim, K>(g, xp, half[p], F_[p], st);
    Mat3 l;
    double vr = 0.0;
    for (int k = 0; k < st.count; ++k) {
      const Vec3& u = vg[st.node[k]];
      for (int i = 0; i < Dim; ++i)
        for (int j = 0; j < Dim; ++j) l(i, j) += u[i] * st.grad[k][j];
      vr += st.w[k] * u[0];
    }
    if (axisym) l(2, 2) = vr / xp[0];
    finish_point(p, l, displacement_[p], dt, bad, out);
  });
  first_bad_ = bad.load();
  first_out_ = out.load();
}

void MpmSolver::update_stress(double dt) {
  const Index n = points_.size();
  ensure_material_groups();
  std::atomic<Index> bad_stress{n};
  for (size_t m = 0; m < materials_.size(); ++m) {
    MaterialBatch b;
    b.points = material_points_[m].data();
    b.count = static_cast<Index>(material_points_[m].size());
    if (b.count == 0) continue;
    b.F_old = nullptr;  // recovered from F_new and L inside the adapter
    b.F_new = F_;
    b.L = L_;
    b.R = points_.view<Mat3>("R");
    b.stress = points_.view<Mat3>("stress");
    b.store = &points_;
    b.dt = dt;
    // Energy: dE = dt <V> <sigma> : D (trapezoidal stress power); plastic dissipation from the model.
    b.volume0 = vol0_;
    b.internal_energy = points_.real("internal_energy");
    b.plastic_energy = points_.real("plastic_work");
    b.first_bad = &bad_stress;
    materials_[m]->update(b);
  }
  if (bad_stress.load() < n) fail(bad_stress.load(), "non-finite stress after the material update");
}

void MpmSolver::handle_exits() {
  const Index n = points_.size();
  if (first_out_ >= n) return;
  if (scenario_.simulation.on_particle_exit != "delete")
    fail(first_out_, "left the grid box (set simulation.on_particle_exit: delete to remove such particles)");
  const auto* x = points_.view<Vec3>("x");
  std::vector<char> keep(n, 1);
  for (Index p = 0; p < n; ++p)
    for (int a = 0; a < dim_; ++a)
      if (!(x[p][a] >= box_lower_[a] && x[p][a] <= box_upper_[a])) keep[p] = 0;
  const auto* v = points_.view<Vec3>("v");
  const auto* mass = points_.real("mass");
  const auto* eint = points_.real("internal_energy");
  for (Index p = 0; p < n; ++p) {
    if (keep[p]) continue;
    removed_mass_ += mass[p];
    removed_momentum_ += mass[p] * v[p];
    removed_energy_ += 0.5 * mass[p] * dot(v[p], v[p]) + eint[p];
  }
  points_.compact(keep);
  groups_dirty_ = true;
}

void MpmSolver::fail(Index p, const std::string& what) const {
  std::ostringstream os;
  os.precision(6);
  const auto* id = points_.ints("id");
  const auto* bid = points_.ints("body");
  const Vec3& x = points_.view<Vec3>("x")[p];
  const Mat3& F = points_.view<Mat3>("F")[p];
  const Mat3& s = points_.view<Mat3>("stress")[p];
  os << "particle " << id[p] << " of body '" << scenario_.bodies.at(bid[p]).name << "' " << what
     << " at step " << steps_ << " (t = " << time_ << " s)\n"
     << "  position [" << x[0] << ", " << x[1] << ", " << x[2] << "] m\n"
     << "  F = [" << F(0, 0) << " " << F(0, 1) << " " << F(0, 2) << "; " << F(1, 0) << " " << F(1, 1)
     << " " << F(1, 2) << "; " << F(2, 0) << " " << F(2, 1) << " " << F(2, 2) << "], J = " << det(F)
     << "\n  stress = [" << s(0, 0) << " " << s(0, 1) << " " << s(0, 2) << "; " << s(1, 0) << " "
     << s(1, 1) << " " << s(1, 2) << "; " << s(2, 0) << " " << s(2, 1) << " " << s(2, 2) << "] Pa";
  throw ParticleError(id[p], os.str());
}

template <int Dim, ShapeKind K>
void MpmSolver::step_impl(double dt) {
  bind_fields();
  build_slabs();
  compute_external_forces();
  particles_to_grid<Dim, K>(false);
  update_grid(dt);
  grid_to_particles<Dim, K>(dt);
  if (musl_) {
    // Map the updated particle momenta back with the same shape functions, then L from them.
    particles_to_grid<Dim, K>(true);
    const Index nn = grid_.geom.node_count();
    for_each(0, nn, [&](Index i) {
      const double m = grid_.mass[i];
      grid_.velocity_new[i] = m > kTinyMass ? (1.0 / m) * grid_.velocity[i] : Vec3{};
    });
    apply_velocity_bcs(grid_.velocity_new);
    velocity_gradient_from_grid<Dim, K>(dt);
  }
  // The step's kinematics are done: count it, so that failure messages, outputs and statistics
  // name the step whose state they show.
  time_ += dt;
  ++steps_;
  if (first_bad_ < points_.size())
    fail(first_bad_, "inverted or non-finite deformation gradient (J <= 0 or NaN)");
  update_stress(dt);
}

void MpmSolver::bind_fields() {
  x_ = points_.view<Vec3>("x");
  F_ = points_.view<Mat3>("F");
  L_ = points_.view<Mat3>("L");
  vol_ = points_.real("volume");
  vol0_ = points_.real("volume0");
}

void MpmSolver::step(double dt) {
  activate_pending();
  if (scenario_.mpm.sort_every > 0 && steps_ % scenario_.mpm.sort_every == 0) sort_by_cell();
  const bool three = dim_ == 3;
  switch (shape_) {
    case ShapeKind::Linear: three ? step_impl<3, ShapeKind::Linear>(dt) : step_impl<2, ShapeKind::Linear>(dt); break;
    case ShapeKind::Gimp: three ? step_impl<3, ShapeKind::Gimp>(dt) : step_impl<2, ShapeKind::Gimp>(dt); break;
    case ShapeKind::Cpdi: three ? step_impl<3, ShapeKind::Cpdi>(dt) : step_impl<2, ShapeKind::Cpdi>(dt); break;
    case ShapeKind::BSpline3: three ? step_impl<3, ShapeKind::BSpline3>(dt) : step_impl<2, ShapeKind::BSpline3>(dt); break;
  }
  handle_exits();
}

EnergyTotals MpmSolver::energies() const {
  const auto* v = points_.view<Vec3>("v");
  const auto* mass = points_.real("mass");
  const auto* eint = points_.real("internal_energy");
  const auto* wp = points_.real("plastic_work");
  double s[7];
  deterministic_sum<7>(0, points_.size(), [&](Index p, double* o) {
    const double m = mass[p];
    o[0] += 0.5 * m * dot(v[p], v[p]);
    o[1] += eint[p];
    o[2] += wp[p];
    o[3] += m;
    o[4] += m * v[p][0];
    o[5] += m * v[p][1];
    o[6] += m * v[p][2];
  }, s);
  comm_.sum(s, 7);
  const double k = reporting_scale();
  EnergyTotals e;
  e.kinetic = k * s[0];
  e.internal = k * s[1];
  e.plastic = k * s[2];
  e.mass = k * s[3];
  // Axisymmetric: only the axial momentum of a body of revolution is non-zero in total.
  e.momentum = Vec3{{dimension_ == Dimension::Axisymmetric ? 0.0 : s[4], k * s[5], k * s[6]}};
  e.external = k * external_work_;
  e.removed_mass = k * removed_mass_;
  e.removed_energy = k * removed_energy_;
  e.removed_momentum = k * removed_momentum_;
  e.inserted_energy = k * comm_.sum(inserted_energy_);
  return e;
}

}  // namespace ballista
