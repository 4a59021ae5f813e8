#include "geometry/cut_lattice.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace ballista {

namespace {

/// A sub-cell with less than this share of its measure inside hands it to a neighbour.
constexpr double kSliverShare = 0.5;

struct CellPart {
  double measure = 0.0;  ///< inside the region: volume, area, or r-weighted area (axisymmetric)
  double size = 0.0;     ///< its volume (3D) or area (2D), unweighted
  Vec3 moment{};         ///< size-weighted position: the part's centroid times its size
  bool whole = false;
};

/// The part of the box centred at x0 (sides d0, d1, d2) inside `region`: the box is divided into
/// kCutSamples boxes per axis; one whose corners are all inside (outside) counts whole (not at
/// all), one the surface crosses is sampled at the centres of kRefine^dim smaller boxes. The
/// surface is thus resolved to d / (kCutSamples kRefine) at the cost of the crossed boxes only.
/// Axisymmetric: the measure is the r-weighted area (exact for whole boxes: r at the centre), and
/// the point sits at the area's centroid, as a whole sub-cell's sits at its centre.
template <class Region>
CellPart sample_part(const Vec3& x0, double d0, double d1, double d2, int dim, bool axisymmetric,
                     const Region& region) {
  const int kRefine = cut_refinement(dim);
  const int m = kCutSamples;
  const int mz = dim == 3 ? m : 0;
  const double d[3] = {d0, d1, dim == 3 ? d2 : 0.0};
  auto corner = [&](int a, int b, int c) {
    return Vec3{{x0[0] + (double(a) / m - 0.5) * d[0], x0[1] + (double(b) / m - 0.5) * d[1],
                 dim == 3 ? x0[2] + (double(c) / m - 0.5) * d[2] : 0.0}};
  };
  std::vector<std::uint8_t> in(static_cast<std::size_t>((m + 1) * (m + 1) * (mz + 1)));
  auto at = [&](int a, int b, int c) -> std::uint8_t& { return in[(c * (m + 1) + b) * (m + 1) + a]; };
  for (int c = 0; c <= mz; ++c)
    for (int b = 0; b <= m; ++b)
      for (int a = 0; a <= m; ++a) at(a, b, c) = region(corner(a, b, c)) ? 1 : 0;
  const double box[3] = {d[0] / m, d[1] / m, dim == 3 ? d[2] / m : 0.0};
  const double box_measure = dim == 3 ? box[0] * box[1] * box[2] : box[0] * box[1];
  CellPart part;
  bool any_out = false;  // corners exactly on the grid box's faces test outside: the samples decide
  for (int c = 0; c < (dim == 3 ? m : 1); ++c)
    for (int b = 0; b < m; ++b)
      for (int a = 0; a < m; ++a) {
        int corners_in = 0, corners = 0;
        for (int cc = 0; cc <= (dim == 3 ? 1 : 0); ++cc)
          for (int bb = 0; bb <= 1; ++bb)
            for (int aa = 0; aa <= 1; ++aa) corners_in += at(a + aa, b + bb, c + cc), ++corners;
        const Vec3 lo = corner(a, b, c);
        if (corners_in == corners) {
          const Vec3 mid{{lo[0] + 0.5 * box[0], lo[1] + 0.5 * box[1], dim == 3 ? lo[2] + 0.5 * box[2] : 0.0}};
          part.measure += (axisymmetric ? mid[0] : 1.0) * box_measure;
          part.size += box_measure;
          part.moment += box_measure * mid;
          continue;
        }
        if (corners_in == 0) {
          any_out = true;
          continue;
        }
        const double w_sample = box_measure / (dim == 3 ? kRefine * kRefine * kRefine : kRefine * kRefine);
        for (int sc = 0; sc < (dim == 3 ? kRefine : 1); ++sc)
          for (int sb = 0; sb < kRefine; ++sb)
            for (int sa = 0; sa < kRefine; ++sa) {
              const Vec3 x{{lo[0] + (sa + 0.5) / kRefine * box[0], lo[1] + (sb + 0.5) / kRefine * box[1],
                            dim == 3 ? lo[2] + (sc + 0.5) / kRefine * box[2] : 0.0}};
              if (!region(x)) {
                any_out = true;
                continue;
              }
              part.measure += (axisymmetric ? x[0] : 1.0) * w_sample;
              part.size += w_sample;
              part.moment += w_sample * x;
            }
      }
  if (!any_out) return CellPart{0.0, 0.0, Vec3{}, true};
  return part;
}

}  // namespace

std::vector<CutLatticePoint> cut_lattice_points(const LatticeSites& sites, int dim, bool axisymmetric,
                                                const std::function<bool(const Vec3&)>& inside) {
  const std::int64_t n[3] = {static_cast<std::int64_t>(sites.at[0].size()),
                             static_cast<std::int64_t>(sites.at[1].size()),
                             static_cast<std::int64_t>(sites.at[2].size())};
  auto flat = [&](std::int64_t i, std::int64_t j, std::int64_t k) { return (k * n[1] + j) * n[0] + i; };
  auto centre = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    return Vec3{{sites.at[0][i], sites.at[1][j], sites.at[2][k]}};
  };
  // A whole sub-cell's volume (3D) or area (2D); its measure is r times that when axisymmetric.
  auto whole_size = [&](std::int64_t i, std::int64_t j, std::int64_t k) {
    const double area = sites.spacing[0][i] * sites.spacing[1][j];
    return dim == 3 ? area * sites.spacing[2][k] : area;
  };
  auto region = [&](const Vec3& x) { return (!axisymmetric || x[0] > 0.0) && inside(x); };
  // The sub-cells of the 3^dim block around (i, j, k) that lie on the lattice, the cell itself too.
  const std::int64_t reach_z = dim == 3 ? 1 : 0;
  auto for_each_neighbour = [&](std::int64_t i, std::int64_t j, std::int64_t k, auto&& visit) {
    for (std::int64_t c = -reach_z; c <= reach_z; ++c)
      for (std::int64_t b = -1; b <= 1; ++b)
        for (std::int64_t a = -1; a <= 1; ++a) {
          const std::int64_t ii = i + a, jj = j + b, kk = k + c;
          visit(ii, jj, kk, ii >= 0 && jj >= 0 && kk >= 0 && ii < n[0] && jj < n[1] && kk < n[2]);
        }
  };

  // Centres inside or out.
  std::vector<std::uint8_t> in(static_cast<std::size_t>(n[0] * n[1] * n[2]), 0);
  for (std::int64_t k = 0; k < n[2]; ++k)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t i = 0; i < n[0]; ++i) in[flat(i, j, k)] = region(centre(i, j, k)) ? 1 : 0;

  // The part of each sub-cell inside: whole or empty when its centre and its neighbours' agree,
  // else sampled (the surface may cross it). Off the lattice counts as outside.
  std::vector<CellPart> part(in.size());
  for (std::int64_t k = 0; k < n[2]; ++k)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t i = 0; i < n[0]; ++i) {
        const std::uint8_t own = in[flat(i, j, k)];
        bool differs = false;
        for_each_neighbour(i, j, k, [&](std::int64_t ii, std::int64_t jj, std::int64_t kk, bool on) {
          differs = differs || (on ? in[flat(ii, jj, kk)] : 0) != own;
        });
        CellPart& c = part[flat(i, j, k)];
        if (!differs) {
          c.whole = own != 0;
          continue;
        }
        c = sample_part(centre(i, j, k), sites.spacing[0][i], sites.spacing[1][j], sites.spacing[2][k], dim,
                        axisymmetric, region);
      }

  // Points: whole sub-cells and parts of at least kSliverShare of theirs; each sliver goes to the
  // kept neighbour whose centre is nearest its centroid. `held` is what each point holds.
  struct Held {
    std::int64_t i, j, k;
    CellPart part;
  };
  std::vector<Held> held;
  std::vector<std::int64_t> point_of(in.size(), -1);
  auto keep = [&](std::int64_t i, std::int64_t j, std::int64_t k, const CellPart& c) {
    point_of[flat(i, j, k)] = static_cast<std::int64_t>(held.size());
    held.push_back({i, j, k, c});
  };
  auto kept = [&](const CellPart& c, std::int64_t i, std::int64_t j, std::int64_t k) {
    return c.whole || (c.measure > 0.0 && c.size >= kSliverShare * whole_size(i, j, k));
  };
  for (std::int64_t k = 0; k < n[2]; ++k)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t i = 0; i < n[0]; ++i)
        if (kept(part[flat(i, j, k)], i, j, k)) keep(i, j, k, part[flat(i, j, k)]);
  const std::size_t first_pass = held.size();
  for (std::int64_t k = 0; k < n[2]; ++k)
    for (std::int64_t j = 0; j < n[1]; ++j)
      for (std::int64_t i = 0; i < n[0]; ++i) {
        const CellPart& c = part[flat(i, j, k)];
        if (!(c.measure > 0.0) || kept(c, i, j, k)) continue;
        const Vec3 centroid = (1.0 / c.size) * c.moment;
        std::int64_t best = -1;
        double nearest = std::numeric_limits<double>::infinity();
        for_each_neighbour(i, j, k, [&](std::int64_t ii, std::int64_t jj, std::int64_t kk, bool on) {
          if (!on) return;
          const std::int64_t q = point_of[flat(ii, jj, kk)];
          if (q < 0 || static_cast<std::size_t>(q) >= first_pass) return;  // slivers take none
          const double dist = norm(centre(ii, jj, kk) - centroid);
          if (dist < nearest) nearest = dist, best = q;
        });
        if (best < 0) {  // no kept neighbour: a point of its own
          keep(i, j, k, c);
          continue;
        }
        CellPart& h = held[static_cast<std::size_t>(best)].part;
        if (h.whole) {  // from now on a part: the whole sub-cell's own measure and moment
          const Held& w = held[static_cast<std::size_t>(best)];
          const double size = whole_size(w.i, w.j, w.k);
          h = CellPart{(axisymmetric ? sites.at[0][w.i] : 1.0) * size, size, size * centre(w.i, w.j, w.k), false};
        }
        h.measure += c.measure;
        h.size += c.size;
        h.moment += c.moment;
      }

  std::vector<CutLatticePoint> points;
  points.reserve(held.size());
  for (const Held& p : held) {
    const double size = whole_size(p.i, p.j, p.k);
    const Vec3 half{{0.5 * sites.spacing[0][p.i], 0.5 * sites.spacing[1][p.j], 0.5 * sites.spacing[2][p.k]}};
    if (p.part.whole) {  // exactly the plain lattice's point
      points.push_back({centre(p.i, p.j, p.k), (axisymmetric ? sites.at[0][p.i] : 1.0) * size, half});
      continue;
    }
    points.push_back({(1.0 / p.part.size) * p.part.moment, p.part.measure,
                      std::pow(p.part.size / size, 1.0 / dim) * half});
  }
  return points;
}

}  // namespace ballista
