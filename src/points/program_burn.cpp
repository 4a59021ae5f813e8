#include "points/program_burn.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>

#include "core/error.hpp"
#include "points/cell_bins.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Cells of one lattice spacing centred on the lattice points: 1 where a cell holds explosive.
/// A summed-volume table of the cells without explosive answers "is every cell of this box
/// explosive?" in O(1), so the line-of-sight test is skipped for points deep inside the charge.
class Occupancy {
 public:
  Occupancy(const Vec3* x, const char* explosive, Index n, double h, int dim) : h_(h), dim_(dim) {
    Vec3 hi;
    for (int a = 0; a < 3; ++a) {
      lo_[a] = kInf;
      hi[a] = -kInf;
    }
    // The box of the explosive points only: their lattice then sits at the cell centres whatever
    // the inert bodies' spacing (an inert lattice offset by half a cell would put explosive points
    // on cell faces), and a large inert target costs no cells. Outside it is non-explosive anyway.
    for (Index p = 0; p < n; ++p)
      if (explosive[p])
        for (int a = 0; a < dim; ++a) {
          lo_[a] = std::min(lo_[a], x[p][a]);
          hi[a] = std::max(hi[a], x[p][a]);
        }
    for (int a = 0; a < 3; ++a) {
      if (a < dim && n > 0) {
        lo_[a] -= 0.5 * h;
        nc_[a] = static_cast<int>(std::floor((hi[a] - lo_[a]) / h)) + 1;
      } else {
        lo_[a] = 0.0;
        nc_[a] = 1;
      }
    }
    cells_.assign(static_cast<size_t>(nc_[0]) * nc_[1] * nc_[2], 0);
    for (Index p = 0; p < n; ++p)
      if (explosive[p]) {
        std::uint8_t& c = cells_[index(x[p])];
        if (c)  // two points in one cell: the charge is not on a lattice of this spacing
          throw Error(fmt::format("program burn: explosive points closer than the lattice spacing {} m (at ({:.6g}, "
                                  "{:.6g}, {:.6g}) m): the explosive bodies must share one lattice",
                                  h, x[p][0], x[p][1], x[p][2]));
        c = 1;
      }
    // Summed-volume table of the cells that are not explosive, with a zero border.
    const size_t s0 = nc_[0] + 1, s1 = nc_[1] + 1, s2 = nc_[2] + 1;
    sum_.assign(s0 * s1 * s2, 0);
    for (int k = 0; k < nc_[2]; ++k)
      for (int j = 0; j < nc_[1]; ++j)
        for (int i = 0; i < nc_[0]; ++i) {
          auto at = [&](int a, int b, int c) -> std::int64_t& { return sum_[(c * s1 + b) * s0 + a]; };
          const std::int64_t hole = cells_[(static_cast<size_t>(k) * nc_[1] + j) * nc_[0] + i] ? 0 : 1;
          at(i + 1, j + 1, k + 1) = hole + at(i, j + 1, k + 1) + at(i + 1, j, k + 1) + at(i + 1, j + 1, k) -
                                    at(i, j, k + 1) - at(i, j + 1, k) - at(i + 1, j, k) + at(i, j, k);
        }
  }

  /// True if every cell within `k` cells of y's cell (a cube, clipped to the box) is explosive and
  /// the cube does not reach past the box (beyond it lies void).
  bool solid_around(const Vec3& y, int k) const {
    int lo[3], hi[3];
    cell(y, lo);
    for (int a = 0; a < 3; ++a) {
      const int c = lo[a];
      const int r = a < dim_ ? k : 0;
      if (c - r < 0 || c + r >= nc_[a]) return false;
      lo[a] = c - r;
      hi[a] = c + r + 1;
    }
    const size_t s0 = nc_[0] + 1, s1 = nc_[1] + 1;
    auto at = [&](int a, int b, int c) { return sum_[(c * s1 + b) * s0 + a]; };
    const std::int64_t holes = at(hi[0], hi[1], hi[2]) - at(lo[0], hi[1], hi[2]) - at(hi[0], lo[1], hi[2]) -
                               at(hi[0], hi[1], lo[2]) + at(lo[0], lo[1], hi[2]) + at(lo[0], hi[1], lo[2]) +
                               at(hi[0], lo[1], lo[2]) - at(lo[0], lo[1], lo[2]);
    return holes == 0;
  }

  /// True if the segment a -> b stays in explosive cells (sampled every h/8). With skip_start
  /// (a detonator, which may sit on the charge's surface, or just outside it) the leading samples
  /// in a's own cell or outside the box are not required to be explosive.
  bool line_of_sight(const Vec3& a, const Vec3& b, bool skip_start = false) const {
    Vec3 d = b - a;
    if (dim_ == 2) d[2] = 0.0;
    const double len = norm(d);
    const int m = std::max(1, static_cast<int>(std::ceil(8.0 * len / h_)));
    int ca[3];
    const bool a_inside = cell(a, ca);
    bool leading = skip_start;
    for (int s = 0; s <= m; ++s) {
      const Vec3 y = a + (static_cast<double>(s) / m) * d;
      int c[3];
      const bool inside = cell(y, c);
      if (leading && (!inside || (a_inside && c[0] == ca[0] && c[1] == ca[1] && c[2] == ca[2]))) continue;
      leading = false;
      if (!inside || !cells_[(static_cast<size_t>(c[2]) * nc_[1] + c[1]) * nc_[0] + c[0]]) return false;
    }
    return true;
  }

 private:
  /// The cell of y; false if y lies outside the box.
  bool cell(const Vec3& y, int c[3]) const {
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      if (a >= dim_) {
        c[a] = 0;
        continue;
      }
      const double f = std::floor((y[a] - lo_[a]) / h_);
      if (f < 0.0 || f >= nc_[a]) inside = false;
      c[a] = static_cast<int>(std::clamp(f, 0.0, static_cast<double>(nc_[a] - 1)));
    }
    return inside;
  }
  size_t index(const Vec3& y) const {
    int c[3];
    cell(y, c);
    return (static_cast<size_t>(c[2]) * nc_[1] + c[1]) * nc_[0] + c[0];
  }

  double h_;
  int dim_;
  Vec3 lo_;
  int nc_[3] = {1, 1, 1};
  std::vector<std::uint8_t> cells_;
  std::vector<std::int64_t> sum_;
};

}  // namespace

ProgramBurnResult program_burn(const Vec3* x, const char* explosive, Index n, const std::vector<Detonator>& detonators,
                               const ProgramBurnOptions& opt) {
  if (!(opt.speed > 0.0) || !(opt.spacing > 0.0) || !(opt.radius_factor >= 1.0))
    throw Error(fmt::format("program burn: detonation speed ({} m/s), spacing ({} m) must be positive and the edge "
                            "radius ({} spacings) at least 1",
                            opt.speed, opt.spacing, opt.radius_factor));
  ProgramBurnResult out;
  out.time.assign(static_cast<size_t>(n), kInf);
  Index n_explosive = 0;
  for (Index p = 0; p < n; ++p) n_explosive += explosive[p] ? 1 : 0;
  if (n_explosive == 0) throw Error("program burn: no point is explosive (no body uses an explosive material)");
  const double radius = opt.radius_factor * opt.spacing;
  const double r2 = radius * radius * (1.0 + 1e-9);  // neighbours exactly at the radius stay in
  const Occupancy occ(x, explosive, n, opt.spacing, opt.dim);
  // Points whose whole edge neighbourhood is explosive need no line-of-sight test.
  const int k = static_cast<int>(std::ceil(opt.radius_factor)) + 1;
  std::vector<char> deep(static_cast<size_t>(n), 0);
  for_each(0, n, [&](Index p) { deep[p] = explosive[p] && occ.solid_around(x[p], k); });
  const CellBins bins(x, n, radius, opt.dim);
  auto dist2 = [&](const Vec3& a, const Vec3& b) {
    Vec3 d = a - b;
    if (opt.dim == 2) d[2] = 0.0;
    return dot(d, d);
  };

  // Path lengths g (m, the detonator's time times D included) and each point's parent: the point
  // or detonator (index n + d) from which the front reaches it in a straight line.
  const Index nd = static_cast<Index>(detonators.size());
  std::vector<double> g(static_cast<size_t>(n), kInf);
  std::vector<Index> parent(static_cast<size_t>(n), -1);
  auto origin = [&](Index a) -> const Vec3& { return a < n ? x[a] : detonators[a - n].x; };
  auto length_to = [&](Index a) { return a < n ? g[a] : detonators[a - n].time * opt.speed; };
  using Entry = std::pair<double, Index>;  // (path length, point): ties go to the lower index
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (Index d = 0; d < nd; ++d) {
    const Detonator& det = detonators[d];
    bool any = false;
    bins.visit(det.x, [&](Index q) {
      if (!explosive[q] || dist2(det.x, x[q]) > r2) return;
      if (!occ.line_of_sight(det.x, x[q], true)) return;
      any = true;
      const double gq = det.time * opt.speed + std::sqrt(dist2(det.x, x[q]));
      if (gq < g[q]) {
        g[q] = gq;
        parent[q] = n + d;
        queue.emplace(gq, q);
      }
    });
    if (!any)
      throw Error(fmt::format("detonation point {} at ({:.6g}, {:.6g}, {:.6g}) m has no explosive point within "
                              "{:.4g} m ({} spacings) in its line of sight: place it in or on the charge",
                              d, det.x[0], det.x[1], det.x[2], radius, opt.radius_factor));
  }
  // Lazy Theta* (Nash, Koenig & Tovey, AAAI 2010) in Dijkstra order: a point reached from q
  // inherits q's parent, as if the front came straight from it (Huygens: the wavelet of the
  // parent); when the point is taken from the queue, the straight line from that parent is
  // checked, and if an obstacle cuts it the point falls back to its best settled neighbour.
  // Paths are then straight in open explosive (exact times there) and bend only at lattice
  // points next to an obstacle's edges.
  auto neighbour_visible = [&](Index p, Index q) { return deep[p] || deep[q] || occ.line_of_sight(x[p], x[q]); };
  std::vector<char> done(static_cast<size_t>(n), 0);
  while (!queue.empty()) {
    const auto [gq, q] = queue.top();
    queue.pop();
    if (done[q] || gq > g[q]) continue;
    const Index pq = parent[q];
    if (!occ.line_of_sight(origin(pq), x[q], pq >= n)) {
      double best = kInf;
      Index arg = -1;
      bins.visit(x[q], [&](Index p) {
        if (!done[p] || dist2(x[p], x[q]) > r2 || !neighbour_visible(p, q)) return;
        const double c = g[p] + std::sqrt(dist2(x[p], x[q]));
        if (c < best || (c == best && p < arg)) {
          best = c;
          arg = p;
        }
      });
      if (arg < 0)  // cannot happen: the point that last lowered g[q] is settled and visible
        throw Error(fmt::format("program burn: internal error, point {} has no settled neighbour in sight", q));
      g[q] = best;
      parent[q] = arg;
    }
    done[q] = 1;
    const Index pp = parent[q];
    bins.visit(x[q], [&](Index s) {
      if (done[s] || !explosive[s] || s == q || dist2(x[q], x[s]) > r2) return;
      const double cand = length_to(pp) + std::sqrt(dist2(origin(pp), x[s]));
      if (!(cand < g[s])) return;
      if (!neighbour_visible(q, s)) return;
      g[s] = cand;
      parent[s] = pp;
      queue.emplace(cand, s);
    });
  }
  for (Index p = 0; p < n; ++p) out.time[p] = g[p] / opt.speed;
  for (Index p = 0; p < n; ++p)
    if (explosive[p] && !std::isfinite(out.time[p])) ++out.unreachable;
  return out;
}

}  // namespace ballista
