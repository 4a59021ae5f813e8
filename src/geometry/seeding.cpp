#include "geometry/seeding.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "core/point_fields.hpp"
#include "geometry/cut_lattice.hpp"
#include "geometry/element_seeding.hpp"
#include "geometry/grid_axes.hpp"
#include "geometry/mesh_solid.hpp"
#include "geometry/shape.hpp"

namespace ballista {

void declare_point_fields(FieldStore& p) {
  // This order is the packing order of migrating points and the checkpoint's layout.
  p.declare(kId, "1");
  p.declare(kBodyIndex, "1");
  p.declare(kMaterialIndex, "1");
  p.declare(kSegment, "1");
  p.declare(kPosition, "m");
  p.declare(kReferencePosition, "m");
  p.declare(kVelocity, "m/s");
  p.declare(kDeformationGradient, "1", true);
  p.declare(kRotation, "1", false);
  p.declare(kVelocityGradient, "1/s", false);
  p.declare(kStress, "Pa");
  p.declare(kMass, "kg");
  p.declare(kReferenceVolume, "m^3");
  p.declare(kVolume, "m^3");
  p.declare(kHalfSize, "m");
  p.declare(kInternalEnergy, "J");
  p.declare(kPlasticWork, "J");
}

std::vector<std::string> extensive_point_fields() {
  return {kMass.name(), kReferenceVolume.name(), kVolume.name(), kInternalEnergy.name(), kPlasticWork.name()};
}

namespace {

/// Lattice points of a body that fall outside the grid box without a symmetry plane to excuse them.
struct ClippedLattice {
  Index count = 0;
  bool sampled = false;  ///< count estimated from a strided sample of a huge bounding box
  bool face[6] = {false, false, false, false, false, false};  ///< faces crossed (x_min .. z_max)
};

/// Counts the shape's lattice point x, outside the grid box, as clipped unless it lies beyond a
/// `symmetry` face whose mirror image is also in the shape (a body cut by its own symmetry plane,
/// e.g. the quarter Taylor bar): that half is represented by the boundary condition, not lost.
void count_if_clipped(const Vec3& x, const GridSpec& grid, int nd, const ShapeSpec& shape, ClippedLattice& clipped) {
  bool inside = true, excused = true;
  bool crossed[6] = {false, false, false, false, false, false};
  Vec3 mirror = x;
  for (int a = 0; a < nd; ++a) {
    int f = -1;
    if (x[a] <= grid.lower[a]) f = 2 * a;
    if (x[a] >= grid.upper[a]) f = 2 * a + 1;
    if (f < 0) continue;
    inside = false;
    crossed[f] = true;
    if (grid.faces[f] != FaceBC::Symmetry) excused = false;
    const double plane = (f % 2) ? grid.upper[a] : grid.lower[a];
    mirror[a] = 2.0 * plane - x[a];
  }
  if (inside || (excused && shape_contains(shape, mirror, nd))) return;
  ++clipped.count;
  for (int f = 0; f < 6; ++f) clipped.face[f] = clipped.face[f] || crossed[f];
}

/// Seeding outside the grid would silently lose mass: a deck error naming the body,
/// the faces it crosses, its extent against the box and the share of the body that would be lost.
[[noreturn]] void throw_clipped_body(const BodySpec& body, const GridSpec& grid, int nd, const ClippedLattice& c,
                                     Index kept) {
  static const char* names[6] = {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
  static const char axes[3] = {'x', 'y', 'z'};
  Vec3 lo, hi;
  shape_bounds(body.shape, nd, lo, hi);
  std::string faces, extent;
  for (int f = 0; f < 2 * nd; ++f) {
    if (!c.face[f]) continue;
    const int a = f / 2;
    faces += (faces.empty() ? "" : ", ") + std::string(names[f]);
    const double over = (f % 2) ? hi[a] - grid.upper[a] : grid.lower[a] - lo[a];
    extent += fmt::format("; along {} the body spans [{:g}, {:g}] m, the grid [{:g}, {:g}] m ({:g} m outside)",
                          axes[a], lo[a], hi[a], grid.lower[a], grid.upper[a], over);
  }
  const double share = static_cast<double>(c.count) / static_cast<double>(c.count + kept);
  throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path,
                  fmt::format("body '{}' is partly outside the grid (beyond {}): {}{} of its {} lattice points "
                              "({:.1f} % of the body) would not be seeded{}; enlarge the grid box or move the body "
                              "(only a body cut by a symmetry face, and mirror-symmetric about it, may extend past "
                              "the box)",
                              body.name, faces, c.sampled ? "about " : "", c.count, c.count + kept, 100.0 * share,
                              extent));
}

/// The lattice sites of a graded grid along each axis within [lo, hi] (one cell beyond, so a
/// shape's boundary sites are all there), with their spacings: n per cell at its sub-cell centres.
struct GraduatedSites {
  std::array<std::vector<double>, 3> at, spacing;
};

/// The sites of `nodes`' cells overlapping [lo, hi] (one cell beyond), n per cell and axis.
void sites_of_cells(const std::vector<double>& node, int n, double lo, double hi, std::vector<double>& at,
                    std::vector<double>& spacing) {
  for (std::size_t c = 0; c + 1 < node.size(); ++c) {
    const double h = node[c + 1] - node[c];
    if (node[c + 1] < lo - h || node[c] > hi + h) continue;
    for (int k = 0; k < n; ++k) {
      at.push_back(node[c] + (k + 0.5) * (h / n));
      spacing.push_back(h / n);
    }
  }
}

/// The lattice of a graded grid over [lo, hi] as blocks of sites: the first on the cells without
/// the patches' splits, whose sites inside a patch are not seeded (`patch` -1), then one per patch
/// on its own cells, whose sites outside it or inside a patch nested in it are not seeded. Without
/// patches, the one block.
struct SiteBlock {
  GraduatedSites sites;
  int patch = -1;
};

std::vector<SiteBlock> graded_site_blocks(const GridSpec& grid, int nd, int n, const Vec3& lo, const Vec3& hi,
                                          GridAxes& axes) {
  axes = build_grid_axes(grid, nd);
  std::vector<SiteBlock> blocks(1 + axes.patches.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    blocks[b].patch = static_cast<int>(b) - 1;
    for (int a = 0; a < 3; ++a) {
      if (a >= nd) {
        blocks[b].sites.at[a] = {0.0};
        blocks[b].sites.spacing[a] = {0.0};
        continue;
      }
      if (b == 0) {
        sites_of_cells(axes.base[a], n, lo[a], hi[a], blocks[b].sites.at[a], blocks[b].sites.spacing[a]);
      } else {
        const PatchBox& p = axes.patches[b - 1];
        sites_of_cells(p.lattice[a], n, std::max(lo[a], p.lower[a]), std::min(hi[a], p.upper[a]),
                       blocks[b].sites.at[a], blocks[b].sites.spacing[a]);
      }
    }
  }
  return blocks;
}

/// Whether block `b`'s site x is seeded: a patch's where it is the deepest patch holding x, the
/// grid's outside every patch.
bool block_keeps(const GridAxes& axes, const SiteBlock& b, const Vec3& x, int nd) {
  return axes.innermost_holding(x, nd) == b.patch;
}

}  // namespace

Index seed_body(const BodySpec& body, int body_index, int material_index, const Material& material,
                const GridSpec& grid, Dimension dim, FieldStore& points, std::int64_t& next_id) {
  if (body.seeding == "elements") return seed_elements(body, body_index, material_index, material, grid, points, next_id);
  const int nd = dim == Dimension::ThreeD ? 3 : 2;
  const double h = grid.cell_size;
  const double dx = seed_spacing(body, h);
  Vec3 lo, hi;
  shape_bounds(body.shape, nd, lo, hi);
  // Lattice aligned with the grid: sub-cell centres grid.lower + (i + 1/2) dx.
  int first[3] = {0, 0, 0}, last[3] = {0, 0, 0};
  for (int k = 0; k < nd; ++k) {
    // Clamped so that a body of absurd size cannot overflow the index (it is reported as clipped).
    first[k] = static_cast<int>(std::clamp(std::floor((lo[k] - grid.lower[k]) / dx), -1.0e9, 1.0e9));
    last[k] = static_cast<int>(std::clamp(std::ceil((hi[k] - grid.lower[k]) / dx), -1.0e9, 1.0e9));
  }
  auto site = [&](int i, int j, int k) {
    return Vec3{{grid.lower[0] + (i + 0.5) * dx, grid.lower[1] + (j + 0.5) * dx,
                 nd == 3 ? grid.lower[2] + (k + 0.5) * dx : 0.0}};
  };
  auto in_box = [&](const Vec3& x) {
    for (int a = 0; a < nd; ++a)
      if (x[a] <= grid.lower[a] || x[a] >= grid.upper[a]) return false;
    return true;
  };
  auto in_cutout = [&](const Vec3& x) {
    for (const ShapeSpec& c : body.cutouts)
      if (shape_contains(c, x, nd)) return true;
    return false;
  };
  // Seeding: the shape's lattice inside the grid box (index ranges clipped to the box plus one
  // layer, so a body far larger than the grid costs only the grid's lattice).
  int from[3] = {first[0], first[1], first[2]}, to[3] = {last[0], last[1], last[2]};
  for (int a = 0; a < nd; ++a) {
    from[a] = std::max(from[a], -1);
    to[a] = std::min(to[a], static_cast<int>(std::ceil((grid.upper[a] - grid.lower[a]) / dx)) + 1);
  }
  std::vector<Vec3> pos;
  std::vector<Vec3> spacing;  // graded grids: each point's lattice spacing per axis
  std::vector<CutLatticePoint> cut;  // seeding: cut_lattice: each point's measure and half size
  if (body.seeding == "cut_lattice") {
    if (grid.graded()) {
      GridAxes axes;
      for (SiteBlock& b : graded_site_blocks(grid, nd, body.particles_per_cell, lo, hi, axes)) {
        LatticeSites sites;
        sites.at = std::move(b.sites.at);
        sites.spacing = std::move(b.sites.spacing);
        const std::vector<CutLatticePoint> part =
            cut_lattice_points(sites, nd, dim == Dimension::Axisymmetric, [&](const Vec3& x) {
              return block_keeps(axes, b, x, nd) && in_box(x) && shape_contains(body.shape, x, nd) && !in_cutout(x);
            });
        cut.insert(cut.end(), part.begin(), part.end());
      }
    } else {
      LatticeSites sites;
      for (int a = 0; a < 3; ++a) {
        if (a >= nd) {
          sites.at[a] = {0.0};
          sites.spacing[a] = {0.0};
          continue;
        }
        for (int i = from[a]; i <= to[a]; ++i) {
          sites.at[a].push_back(grid.lower[a] + (i + 0.5) * dx);
          sites.spacing[a].push_back(dx);
        }
      }
      cut = cut_lattice_points(sites, nd, dim == Dimension::Axisymmetric, [&](const Vec3& x) {
        return in_box(x) && shape_contains(body.shape, x, nd) && !in_cutout(x);
      });
    }
    for (const CutLatticePoint& c : cut) pos.push_back(c.at);
  } else if (!grid.graded()) {
    for (int k = from[2]; k <= to[2]; ++k)
      for (int j = from[1]; j <= to[1]; ++j)
        for (int i = from[0]; i <= to[0]; ++i) {
          const Vec3 x = site(i, j, k);
          if (dim == Dimension::Axisymmetric && !(x[0] > 0.0)) continue;  // r > 0 only
          if (in_box(x) && shape_contains(body.shape, x, nd) && !in_cutout(x)) pos.push_back(x);
        }
  } else {
    // Graded grid: particles_per_cell sites per axis in every cell, at its sub-cell centres, so
    // the particles are as fine as the cells they start in (a patch's split cells inside it).
    GridAxes axes;
    for (const SiteBlock& b : graded_site_blocks(grid, nd, body.particles_per_cell, lo, hi, axes)) {
      const GraduatedSites& sites = b.sites;
      for (std::size_t k = 0; k < sites.at[2].size(); ++k)
        for (std::size_t j = 0; j < sites.at[1].size(); ++j)
          for (std::size_t i = 0; i < sites.at[0].size(); ++i) {
            const Vec3 x{{sites.at[0][i], sites.at[1][j], nd == 3 ? sites.at[2][k] : 0.0}};
            if (dim == Dimension::Axisymmetric && !(x[0] > 0.0)) continue;
            if (block_keeps(axes, b, x, nd) && in_box(x) && shape_contains(body.shape, x, nd) && !in_cutout(x)) {
              pos.push_back(x);
              spacing.push_back(
                  Vec3{{sites.spacing[0][i], sites.spacing[1][j], nd == 3 ? sites.spacing[2][k] : 0.0}});
            }
          }
    }
  }
  // Clipping: lattice points of the shape outside the box. Every one is visited while
  // the bounding box has at most kExhaustive lattice points; beyond that a regular sample with
  // stride s per axis is taken and the count scaled by s^nd (a body that large is outside anyway).
  constexpr double kExhaustive = 2.0e7;
  double sites = 1.0;
  for (int a = 0; a < nd; ++a) sites *= static_cast<double>(last[a] - first[a] + 1);
  const int stride = sites <= kExhaustive ? 1 : static_cast<int>(std::ceil(std::pow(sites / kExhaustive, 1.0 / nd)));
  ClippedLattice clipped;
  for (int k = first[2]; k <= last[2]; k += (nd == 3 ? stride : 1))
    for (int j = first[1]; j <= last[1]; j += stride)
      for (int i = first[0]; i <= last[0]; i += stride) {
        const Vec3 x = site(i, j, k);
        if (in_box(x)) continue;
        if (dim == Dimension::Axisymmetric && !(x[0] > 0.0)) continue;  // r > 0 only: not a clip
        if (!shape_contains(body.shape, x, nd) || in_cutout(x)) continue;
        count_if_clipped(x, grid, nd, body.shape, clipped);
      }
  clipped.count *= static_cast<Index>(std::pow(static_cast<double>(stride), nd));
  clipped.sampled = stride > 1;
  if (clipped.count > 0) throw_clipped_body(body, grid, nd, clipped, static_cast<Index>(pos.size()));
  if (pos.empty()) {
    // Inside the box but between lattice sites: a body thinner than the spacing along some axis.
    static const char axes[3] = {'x', 'y', 'z'};
    for (int a = 0; a < nd; ++a)
      if (hi[a] - lo[a] < dx)
        throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path,
                        fmt::format("body '{}' is {:g} m thick along {}, less than its lattice spacing {:g} m, so "
                                    "no particle lies inside it: refine the lattice (grid.cell_size, the body's "
                                    "particles_per_cell or point_spacing)",
                                    body.name, hi[a] - lo[a], axes[a], dx));
    throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path,
                    "body '" + body.name +
                        "' has no particles inside the grid: check its shape, the grid box and cell_size");
  }

  const Index n = static_cast<Index>(pos.size());
  SeededPoints seeded(points, n);
  const double uniform_cell_volume = nd == 3 ? dx * dx * dx : dx * dx;
  for (Index q = 0; q < n; ++q) {
    const Vec3 d = spacing.empty() ? Vec3{{dx, dx, nd == 3 ? dx : 0.0}} : spacing[q];
    const double cell_volume = spacing.empty() ? uniform_cell_volume : (nd == 3 ? d[0] * d[1] * d[2] : d[0] * d[1]);
    Vec3 v = body.velocity;
    if (body.radial_speed != 0.0) {  // radially away from the axis of the body's cylinder or tube
      const int ax = body.shape.axis;
      Vec3 r = pos[q] - body.shape.center;
      r[ax] = 0.0;
      const double len = norm(r);
      if (len > 0.0) v += (body.radial_speed / len) * r;
    }
    if (nd == 2) v[2] = 0.0;
    if (!cut.empty()) {
      seeded.set(q, next_id, body_index, material_index, material.density(), pos[q], v, cut[q].measure, cut[q].half);
      continue;
    }
    // Axisymmetric: volume per radian = r * area (thesis seed 000 ch. 5 uses Uintah's convention).
    const double volume = dim == Dimension::Axisymmetric ? pos[q][0] * cell_volume : cell_volume;
    seeded.set(q, next_id, body_index, material_index, material.density(), pos[q], v, volume,
               Vec3{{0.5 * d[0], 0.5 * d[1], nd == 3 ? 0.5 * d[2] : 0.0}});
  }
  return n;
}

SeededPoints::SeededPoints(FieldStore& points, Index n) : first_(points.size()) {
  points.resize(first_ + n);
  id_ = points.ints(kId);
  body_ = points.ints(kBodyIndex);
  material_ = points.ints(kMaterialIndex);
  x_ = points.view(kPosition);
  x0_ = points.view(kReferencePosition);
  v_ = points.view(kVelocity);
  F_ = points.view(kDeformationGradient);
  R_ = points.view(kRotation);
  mass_ = points.real(kMass);
  vol0_ = points.real(kReferenceVolume);
  vol_ = points.real(kVolume);
  half_ = points.view(kHalfSize);
}

void SeededPoints::set(Index q, std::int64_t& next_id, int body_index, int material_index, double rho0, const Vec3& at,
                       const Vec3& v, double volume, const Vec3& half_size) {
  const Index p = first_ + q;
  id_[p] = next_id++;
  body_[p] = body_index;
  material_[p] = material_index;
  x_[p] = at;
  x0_[p] = at;
  v_[p] = v;
  F_[p] = Mat3::identity();
  R_[p] = Mat3::identity();
  vol0_[p] = volume;
  vol_[p] = volume;
  mass_[p] = rho0 * volume;
  half_[p] = half_size;
}

double lattice_point_bound(const BodySpec& body, const GridSpec& grid, Dimension dim) {
  if (body.seeding == "elements") return static_cast<double>(element_mesh(body).mesh().tets.size());
  const int nd = dim == Dimension::ThreeD ? 3 : 2;
  const double dx = seed_spacing(body, grid.cell_size);
  auto bound = [&](const ShapeSpec& shape) {
    Vec3 lo, hi;
    shape_bounds(shape, nd, lo, hi);
    double n = 1.0;
    if (grid.graded()) {  // the graded lattice's sites over the bounding box, every block's
      GridAxes axes;
      n = 0.0;
      for (const SiteBlock& b : graded_site_blocks(grid, nd, body.particles_per_cell, lo, hi, axes)) {
        double m = 1.0;
        for (int a = 0; a < nd; ++a) m *= static_cast<double>(b.sites.at[a].size());
        n += m;
      }
      return n;
    }
    for (int a = 0; a < nd; ++a) {
      const double extent = std::min(hi[a], grid.upper[a]) - std::max(lo[a], grid.lower[a]);
      n *= extent > 0.0 ? std::floor(extent / dx) + 1.0 : 0.0;
    }
    return n;
  };
  if (body.segments.empty()) return bound(body.shape);
  double n = 0.0;
  for (const auto& s : body.segments) n += bound(s.shape);
  return n;
}

Index mark_pressure_surface(const LoadSpec& load, int k, const BodySpec& body, int body_index,
                            double h, Dimension dim, FieldStore& points) {
  const std::string& surface = load.params.choices.at("surface");
  const std::string field = "load_area_" + std::to_string(k);
  const double hole_radius = load.params.number_or("hole_radius", 0.0);
  points.add_real(field, 3, "m^2", false);
  const int nd = dim == Dimension::ThreeD ? 3 : 2;
  const double dx = seed_spacing(body, h);
  const ShapeSpec& s = body.shape;
  const auto* bid = points.ints(kBodyIndex);
  const auto* x0 = points.view(kReferencePosition);
  const auto* vol0 = points.real(kReferenceVolume);
  const auto* half = points.view(kHalfSize);
  auto* area = points.view<Vec3>(field);
  Index marked = 0;
  for (Index p = 0; p < points.size(); ++p) {
    if (bid[p] != body_index) continue;
    const Vec3& X = x0[p];
    Vec3 N;  // outward unit normal of the surface at the point
    double depth = -1.0;  // distance of the point inside the surface, m
    double curvature_scale = 1.0;  // surface area / band-layer area at the point's depth
    if (s.type == "box") {
      static const char* names[6] = {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
      for (int f = 0; f < 2 * nd; ++f) {
        if (surface != names[f]) continue;
        const int a = f / 2;
        depth = (f % 2) ? s.upper[a] - X[a] : X[a] - s.lower[a];
        N[a] = (f % 2) ? 1.0 : -1.0;
      }
    } else if (s.type == "sphere") {
      Vec3 d = X - s.center;
      if (nd == 2) d[2] = 0.0;
      const double r = norm(d);
      if (surface == "outer" && r > 0.0) {
        depth = s.radius - r;
        N = (1.0 / r) * d;
        curvature_scale = nd == 3 ? (s.radius * s.radius) / (r * r) : s.radius / r;
      }
    } else {  // cylinder / tube: outer, inner, top, bottom
      const int a = (nd == 2 && s.axis == 2) ? -1 : s.axis;
      Vec3 d = X - s.center;
      if (a >= 0) d[a] = 0.0;
      if (nd == 2) d[2] = 0.0;  // 2D: the radius lies in the x-y plane (axisymmetric: r = x)
      const double r = norm(d);
      // Curved faces (not in axisymmetric runs, where the r-z section is straight): the band at
      // radius r represents the surface at radius R, whose area is larger by R / r.
      const bool curved = !(dim == Dimension::Axisymmetric);
      if (surface == "outer") {
        depth = s.radius - r;
        N = (1.0 / r) * d;
        if (curved) curvature_scale = s.radius / r;
      }
      if (surface == "inner") {
        depth = r - s.inner_radius;
        N = (-1.0 / r) * d;
        if (curved) curvature_scale = s.inner_radius / r;
      }
      if (a >= 0 && surface == "top") { depth = s.center[a] + s.length - X[a]; N[a] = 1.0; }
      if (a >= 0 && surface == "bottom") { depth = X[a] - s.center[a]; N[a] = -1.0; }
      // A hole in the loaded end face around the axis, through which a penetrator enters without
      // dragging loaded surface points into its channel (thesis seed 000 §6.2 and Fig. 6.14).
      if ((surface == "top" || surface == "bottom") && r < hole_radius) continue;
    }
    // Band of lattice points carrying the surface: depth in [0, w) with w = dx max_i |N_i|. A
    // lattice column along the dominant normal axis then holds exactly one point of the band, so
    // giving each point the area V0 / w makes the band's total area equal the surface's for a
    // flat surface at any inclination (staircase-seeded). On a curved surface the band point at
    // radius r stands for surface at radius R: the area is scaled by (R/r) per curved direction,
    // leaving an O(dx^2/R^2) lattice error.
    const double mx = std::max({std::abs(N[0]), std::abs(N[1]), std::abs(N[2])});
    // The lattice spacing along the dominant normal axis: the point's own (a graded grid's
    // particles are as fine as their cells; 2 * half_size = dx exactly on a uniform lattice).
    const int dominant = std::abs(N[0]) == mx ? 0 : (std::abs(N[1]) == mx ? 1 : 2);
    const double w = 2.0 * half[p][dominant] * mx;
    if (!(depth >= -1e-12 * dx && depth < w)) continue;
    // Axisymmetric: vol0 = r_p dA carries the point's radius, but the surface element's per-radian
    // area is r_s ds at the surface radius r_s = r_p + depth N_r (the point projected onto the
    // surface along N); without this the cylindrical faces get (1 -+ depth/r) of their area.
    const double r_scale = dim == Dimension::Axisymmetric ? (X[0] + depth * N[0]) / X[0] : 1.0;
    area[p] = (curvature_scale * r_scale * vol0[p] / w) * N;
    ++marked;
  }
  return marked;
}

}  // namespace ballista
