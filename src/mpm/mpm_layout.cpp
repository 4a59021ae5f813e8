// The MPM solver's grid and its construction: the box with its ghost layers (uniform or graded),
// the memory estimate of the grid arrays, the particles seeded and, on several ranks, shared out.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
#include "geometry/grid_axes.hpp"
#include "geometry/seeding.hpp"
#include "mpm/mpm_params.hpp"
#include "mpm/mpm_solver.hpp"
#include "points/point_exchange.hpp"

namespace ballista {

namespace {
int axis_count(Dimension d) { return d == Dimension::ThreeD ? 3 : 2; }

/// The solver's own storage per point, for the memory estimate: GIMP's windows kept for the step.
double bytes_per_point(const Scenario& sc) {
  if (read_mpm_params(sc.solver_params).shape != ShapeKind::Gimp) return 0.0;
  return sc.simulation.dimension == Dimension::ThreeD ? sizeof(GimpWindows<3>) : sizeof(GimpWindows<2>);
}
}  // namespace

MpmSolver::GridLayout MpmSolver::layout_grid(const Scenario& sc, int ghost) {
  if (sc.grid.graded()) return layout_graded_grid(sc, ghost);
  // Grid block: the physical box plus ghost node layers so every stencil stays in the block.
  GridLayout L;
  const Dimension dimension = sc.simulation.dimension;
  const int dim = axis_count(dimension);
  const double h = sc.grid.cell_size;
  GridGeometry& g = L.geom;
  g.h = h;
  g.dim = dim;
  for (int a = 0; a < 3; ++a) {
    if (a < dim) {
      const int cells = static_cast<int>(std::ceil((sc.grid.upper[a] - sc.grid.lower[a]) / h - 1e-9));
      L.box_lower[a] = sc.grid.lower[a];
      L.box_upper[a] = sc.grid.lower[a] + cells * h;
      g.origin[a] = sc.grid.lower[a] - ghost * h;
      g.nodes[a] = cells + 1 + 2 * ghost;
      L.box_first[a] = ghost;
      L.box_last[a] = ghost + cells;
    } else {
      L.box_lower[a] = L.box_upper[a] = g.origin[a] = 0.0;
      g.nodes[a] = 1;
      L.box_first[a] = L.box_last[a] = 0;
    }
  }
  return L;
}

MpmSolver::GridLayout MpmSolver::layout_graded_grid(const Scenario& sc, int ghost) {
  // The box's graded axes (geometry/grid_axes.hpp), each continued by `ghost` cells of its end
  // cells' size on either side.
  GridLayout L;
  const int dim = axis_count(sc.simulation.dimension);
  const GridAxes axes = build_grid_axes(sc.grid, dim);
  GridGeometry& g = L.geom;
  g.dim = dim;
  g.h = sc.grid.cell_size;
  auto graded = std::make_shared<std::array<GradedAxis, 3>>();
  for (int a = 0; a < 3; ++a) {
    if (a >= dim) {
      L.box_lower[a] = L.box_upper[a] = g.origin[a] = 0.0;
      g.nodes[a] = 1;
      L.box_first[a] = L.box_last[a] = 0;
      continue;
    }
    const std::vector<double>& box = axes.node[a];
    const std::vector<double> nodes = with_ghost_layers(box, ghost);
    (*graded)[a] = GradedAxis(nodes);
    g.origin[a] = nodes.front();
    g.nodes[a] = static_cast<int>(nodes.size());
    g.h = std::min(g.h, axes.smallest(a));
    L.box_lower[a] = box.front();
    L.box_upper[a] = box.back();
    L.box_first[a] = ghost;
    L.box_last[a] = ghost + axes.cells(a);
  }
  g.graded = std::move(graded);
  return L;
}

namespace {
/// The extra node arrays a deck asks for (MpmParams::extra_node_arrays).
int extra_node_arrays(const Scenario& sc) { return read_mpm_params(sc.solver_params).extra_node_arrays(); }

/// Grid storage per node and velocity field, for the memory estimate: mass; velocity, force,
/// velocity_new, accel; several fields: grad, impulse, friction_impulse; the extra arrays.
double bytes_per_node(int fields, int extra) {
  return fields * (sizeof(double) + 4 * sizeof(Vec3) + (fields > 1 ? 3 * sizeof(Vec3) : 0) + extra * sizeof(Vec3));
}

double grid_bytes(const GridGeometry& g, int fields, int extra) {
  return static_cast<double>(g.node_count()) * bytes_per_node(fields, extra);
}
}  // namespace

MpmSolver::MpmSolver(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, Communicator comm)
    : scenario_(sc),
      comm_(comm),
      layout_(layout_grid(sc, kGhostLayers)),
      pts_(sc, std::move(materials), SeedLattice{sc.grid, 0, bytes_per_point(sc)},
           grid_bytes(layout_.geom, sc.contact.fields, extra_node_arrays(sc)),
           fmt::format("{:.3g} grid nodes x {:g} B", static_cast<double>(layout_.geom.node_count()),
                       bytes_per_node(sc.contact.fields, extra_node_arrays(sc))),
           comm),
      points_(pts_.store()),
      partition_(comm, axis_count(sc.simulation.dimension)) {
  dimension_ = sc.simulation.dimension;
  dim_ = axis_count(dimension_);
  const MpmParams P = read_mpm_params(sc.solver_params);
  shape_ = P.shape;
  musl_ = P.update == MpmParams::Update::Musl;
  usavg_ = P.update == MpmParams::Update::Usavg;
  bulk_viscosity_ = P.bulk_viscosity;
  if (bulk_viscosity_.active()) pts_.declare(kBulkViscosity, "Pa");
  flip_ = P.flip;
  pts_.set_distortion_limit(P.distortion_limit);
  xpic_order_ = P.xpic_order;
  sort_every_ = P.sort_every;
  anti_locking_ = P.anti_locking;
  fbar_.set_patch(P.fbar_patch);
  rebalance_ = P.rebalance_imbalance;
  damping_ = sc.simulation.damping;
  grid_.geom = layout_.geom;
  grid_.fields = sc.contact.fields;
  grid_.with_volume = grid_.fields > 1 && sc.contact.min_volume_fraction > 0.0;
  slab_axis_ = dim_ - 1;
  grid_.resize(grid_.geom.node_count() * grid_.fields);
  blocks_.reset(grid_.geom);
  if (shape_ == ShapeKind::BSpline3) {
    // The cubic B-spline reaches one node beyond the face cell. Fixed and wall faces bound the
    // basis (Steffen, Wallstedt et al., CMES 31 (2008) 107: boundary-modified, interpolatory at
    // the face, so the face nodes' condition holds for the material at the face). Symmetry faces
    // and the axis of an axisymmetric grid continue it by the mirror image of the grid field
    // (image particles: the ghost nodes carry the mirrored inside values), which is the exact
    // half of the symmetric whole-body problem. Free faces keep the uniform basis on the ghost
    // layers (as in the interior). docs/deck.md, mpm.shape_function.
    for (int a = 0; a < dim_; ++a)
      for (int side = 0; side < 2; ++side) {
        const FaceBC bc = sc.grid.faces[2 * a + side];
        const int node = side == 0 ? layout_.box_first[a] : layout_.box_last[a];
        const bool axis = dimension_ == Dimension::Axisymmetric && a == 0 && side == 0 && layout_.box_lower[0] == 0.0;
        if (bc == FaceBC::Fixed || bc == FaceBC::Wall) {
          (side == 0 ? spline_faces_.lo : spline_faces_.hi)[a] = node;
        } else if (bc == FaceBC::Symmetry || axis) {
          mirror_faces_.push_back({a, node, side == 0 ? -1 : 1});
        }
      }
  }
  if (grid_.geom.graded && shape_ == ShapeKind::BSpline3)
    throw_solver_param_error(sc, "mpm", "shape_function",
                             "bspline3 does not run on a graded grid (grid.refine) yet: its basis on unequal cells "
                             "(non-uniform knots) is not implemented; use gimp, linear or cpdi");
  if (grid_.geom.graded && comm_.distributed()) {
    const bool bands = !sc.grid.refine.empty();
    const DeckMark& m = bands ? sc.grid.refine_mark : sc.grid.patches.front().mark;
    throw DeckError(m.file, m.line, m.column, bands ? "grid.refine" : "grid.patches",
                    "a graded grid runs on one MPI rank only so far (" + std::to_string(comm_.size()) +
                        " ranks were started; docs/parallel.md)");
  }
  if (!sc.grid.patches.empty()) setup_patches(sc);
  if (P.fbar_patch > 1 && anti_locking_ != AntiLocking::FBar)
    throw_solver_param_error(sc, "mpm", "fbar_patch",
                             "is the F-bar's patch and does nothing without anti_locking: fbar (set it, or remove "
                             "fbar_patch)");
  if (P.fbar_patch > 1 && comm_.distributed())
    // A patch is keyed by its corner cell, which a rank holding another part of the patch need
    // not share: the per-patch sums would not meet across ranks.
    throw_solver_param_error(sc, "mpm", "fbar_patch",
                             "F-bar patches larger than a cell run on one MPI rank only so far (" +
                                 std::to_string(comm_.size()) + " ranks were started; docs/parallel.md)");
  if (usavg_ && shape_ == ShapeKind::Cpdi)
    // CPDI's domains follow F, which the first stress half changes within the step: the second
    // mapping and the update would use other weights than the first, and momentum would drift.
    throw_solver_param_error(sc, "mpm", "update",
                             "usavg does not work with shape_function: cpdi yet (its weights follow F, which the "
                             "first half of the stress update changes within the step); use gimp or bspline3");
  multirate_max_ = P.multirate_max_ratio;
  if (multirate_max_ > 1) {
    // What the multi-rate step does not do yet (mpm_multirate.cpp): it is USAVG's scheme, on one
    // rank, without the F-bar's cell sums or XPIC's grid passes.
    const char* why = !usavg_                              ? "works with update: usavg only so far"
                      : comm_.distributed()                ? "runs on one MPI rank only so far"
                      : anti_locking_ == AntiLocking::FBar ? "does not work with anti_locking: fbar yet"
                      : xpic_order_ > 1 && flip_ < 1.0     ? "does not work with xpic_order > 1 yet"
                                                           : nullptr;
    if (why) throw_solver_param_error(sc, "mpm", "multirate", std::string("multi-rate stepping ") + why);
  }
  if (comm_.distributed()) {
    // Every rank seeded every body: keep a share, then the first partition moves each particle to
    // the rank owning its region.
    pts_.keep_share(comm_);
    migrated_ += static_cast<double>(comm_.sum(static_cast<std::int64_t>(cut_and_migrate())));
  }
  sort_by_cell();
}

}  // namespace ballista
