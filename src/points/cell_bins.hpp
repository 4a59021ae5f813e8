#pragma once
// Cell binning of points for neighbour searches (peridynamic bond families and contact list, the
// OTM supports): the points' bounding box cut into bins of a given size, a stable counting sort of
// the points into them, and a visit of the points in the 3^dim bins around a position. O(N) to
// build; a search of radius at most the bin size finds every neighbour in the surrounding bins.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista {

class CellBins {
 public:
  /// Bins of at least `size` over the points x[0..n) (z ignored in 2D). The bins are enlarged while
  /// there would be more than 4n + 1024 of them (points spread far apart: fragments in flight).
  CellBins(const Vec3* x, Index n, double size, int dim) : dim_(dim), size_(size) {
    lo_ = Vec3{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                std::numeric_limits<double>::infinity()}};
    Vec3& hi = hi_;
    hi = -1.0 * lo_;
    for (Index p = 0; p < n; ++p)
      for (int a = 0; a < dim; ++a) {
        lo_[a] = std::min(lo_[a], x[p][a]);
        hi[a] = std::max(hi[a], x[p][a]);
      }
    auto along = [&](int a) { return a < dim && n > 0 ? (hi[a] - lo_[a]) / size_ + 1.0 : 1.0; };
    while (along(0) * along(1) * along(2) > 4.0 * static_cast<double>(n) + 1024.0) size_ *= 2.0;
    for (int a = 0; a < 3; ++a)
      nb_[a] = a < dim && n > 0 ? std::max(1, static_cast<int>((hi[a] - lo_[a]) / size_) + 1) : 1;
    const Index nbins = static_cast<Index>(nb_[0]) * nb_[1] * nb_[2];
    // Counting sort (stable: each bin's points in increasing index).
    start_.assign(static_cast<size_t>(nbins) + 1, 0);
    order_.resize(static_cast<size_t>(n));
    std::vector<Index> bin(static_cast<size_t>(n));
    for (Index p = 0; p < n; ++p) {
      int c[3];
      cell(x[p], c);
      bin[p] = (static_cast<Index>(c[2]) * nb_[1] + c[1]) * nb_[0] + c[0];
      ++start_[bin[p] + 1];
    }
    for (Index b = 0; b < nbins; ++b) start_[b + 1] += start_[b];
    std::vector<Index> fill(start_.begin(), start_.end() - 1);
    for (Index p = 0; p < n; ++p) order_[fill[bin[p]]++] = p;
  }

  /// False if y is farther than `reach` bins outside the points' bounding box along some axis: no
  /// point is within reach bin sizes of it (visit would clamp it into the edge bins and scan them
  /// for nothing).
  bool near(const Vec3& y, int reach = 1) const {
    const double margin = reach * size_;
    for (int a = 0; a < dim_; ++a)
      if (!(y[a] >= lo_[a] - margin && y[a] <= hi_[a] + margin)) return false;
    return true;
  }

  /// The bin size actually used (at least the one asked for).
  double size() const { return size_; }

  /// Number of bins, and the positions in order() of bin b's points: [first, last).
  Index bin_count() const { return static_cast<Index>(start_.size()) - 1; }
  Index bin_first(Index b) const { return start_[b]; }
  Index bin_last(Index b) const { return start_[b + 1]; }

  /// Calls f(b2) for every bin b2 within one bin of bin b along each axis (b itself included).
  template <class F>
  void visit_neighbour_bins(Index b, F&& f) const {
    const int c0 = static_cast<int>(b % nb_[0]), c1 = static_cast<int>((b / nb_[0]) % nb_[1]),
              c2 = static_cast<int>(b / (static_cast<Index>(nb_[0]) * nb_[1]));
    const int zr = dim_ == 3 ? 1 : 0;
    for (int dz = -zr; dz <= zr; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int b0 = c0 + dx, b1 = c1 + dy, b2 = c2 + dz;
          if (b0 < 0 || b1 < 0 || b2 < 0 || b0 >= nb_[0] || b1 >= nb_[1] || b2 >= nb_[2]) continue;
          f((static_cast<Index>(b2) * nb_[1] + b1) * nb_[0] + b0);
        }
  }

  /// The points in bin order (bin by bin, each bin's in increasing index): arrays permuted so and
  /// binned again are scanned contiguously by visit.
  const std::vector<Index>& order() const { return order_; }

  /// For every bin, its chessboard distance in bins to the nearest bin holding a point, capped at
  /// `cap` (all `cap` without points). Two-pass chamfer over the 3^dim neighbourhood with unit
  /// weights, exact for the chessboard metric (Rosenfeld & Pfaltz, J. ACM 13 (1966) 471). A point
  /// in bin b is at least (d[b] - 1) bin sizes from every binned point, along one axis.
  std::vector<std::uint8_t> chessboard_distance(std::uint8_t cap) const {
    const Index nbins = static_cast<Index>(nb_[0]) * nb_[1] * nb_[2];
    std::vector<std::uint8_t> d(static_cast<size_t>(nbins), cap);
    for (Index b = 0; b < nbins; ++b)
      if (start_[b + 1] > start_[b]) d[b] = 0;
    auto pass = [&](int sign) {
      for (Index i = 0; i < nbins; ++i) {
        const Index b = sign > 0 ? i : nbins - 1 - i;
        std::uint8_t best = d[b];
        visit_neighbour_bins(b, [&](Index c) {
          // Only the neighbours already visited in this pass's order (raster before b, or after).
          if (sign > 0 ? c >= b : c <= b) return;
          if (d[c] + 1 < best) best = static_cast<std::uint8_t>(d[c] + 1);
        });
        d[b] = best;
      }
    };
    pass(+1);
    pass(-1);
    return d;
  }

  /// How far y lies outside the points' bounding box along the farthest axis (0 inside): every
  /// binned point is at least this far from y (a position clamped into the edge bins is farther
  /// from the points than its bin says).
  double outside_distance(const Vec3& y) const {
    double d = 0.0;
    for (int a = 0; a < dim_; ++a) d = std::max({d, lo_[a] - y[a], y[a] - hi_[a]});
    return d;
  }

  /// The bin of position y (clamped into the bins), as an index into chessboard_distance().
  Index bin_of(const Vec3& y) const {
    int c[3];
    cell(y, c);
    return (static_cast<Index>(c[2]) * nb_[1] + c[1]) * nb_[0] + c[0];
  }

  /// Calls f(q) for every point q in the bins around position y (q may be the point at y itself):
  /// those within `reach` bins along each axis (1: the 3^dim bins, every point within a bin size).
  template <class F>
  void visit(const Vec3& y, F&& f, int reach = 1) const {
    int c[3];
    cell(y, c);
    const int zr = dim_ == 3 ? reach : 0;
    for (int dz = -zr; dz <= zr; ++dz)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dx = -reach; dx <= reach; ++dx) {
          const int b0 = c[0] + dx, b1 = c[1] + dy, b2 = c[2] + dz;
          if (b0 < 0 || b1 < 0 || b2 < 0 || b0 >= nb_[0] || b1 >= nb_[1] || b2 >= nb_[2]) continue;
          const Index b = (static_cast<Index>(b2) * nb_[1] + b1) * nb_[0] + b0;
          for (Index i = start_[b]; i < start_[b + 1]; ++i) f(order_[i]);
        }
  }

  /// Calls f(q) for every point q in the bins within `reach` bins of y whose box comes within
  /// `radius` of y: visit() without the corner bins that hold no point within radius (a sphere
  /// meets ~2/3 of its box of bins), the points in visit()'s order. radius <= reach * size().
  template <class F>
  void visit_within(const Vec3& y, double radius, F&& f, int reach = 1) const {
    constexpr int kMaxReach = 8;
    if (reach > kMaxReach) {
      visit(y, f, reach);
      return;
    }
    int c[3];
    cell(y, c);
    // Squared gap between y and the bins at offset k along each axis (0 for y's own slab).
    double gap2[3][2 * kMaxReach + 1] = {};
    for (int a = 0; a < dim_; ++a)
      for (int k = -reach; k <= reach; ++k) {
        const double lo = lo_[a] + (c[a] + k) * size_, hi = lo + size_;
        const double g = std::max({0.0, lo - y[a], y[a] - hi});
        gap2[a][k + reach] = g * g;
      }
    // A hair of slack: a bin's box is computed, and a point on its face may round to either side.
    const double r2 = radius * radius * (1.0 + 1e-9);
    const int zr = dim_ == 3 ? reach : 0;
    for (int dz = -zr; dz <= zr; ++dz) {
      const double gz = gap2[2][dz + reach];
      if (gz > r2) continue;
      for (int dy = -reach; dy <= reach; ++dy) {
        const double gyz = gz + gap2[1][dy + reach];
        if (gyz > r2) continue;
        for (int dx = -reach; dx <= reach; ++dx) {
          if (gyz + gap2[0][dx + reach] > r2) continue;
          const int b0 = c[0] + dx, b1 = c[1] + dy, b2 = c[2] + dz;
          if (b0 < 0 || b1 < 0 || b2 < 0 || b0 >= nb_[0] || b1 >= nb_[1] || b2 >= nb_[2]) continue;
          const Index b = (static_cast<Index>(b2) * nb_[1] + b1) * nb_[0] + b0;
          for (Index i = start_[b]; i < start_[b + 1]; ++i) f(order_[i]);
        }
      }
    }
  }

 private:
  void cell(const Vec3& y, int c[3]) const {
    for (int a = 0; a < 3; ++a)
      c[a] = a < dim_ ? std::clamp(static_cast<int>((y[a] - lo_[a]) / size_), 0, nb_[a] - 1) : 0;
  }

  int dim_;
  double size_;
  Vec3 lo_, hi_;
  int nb_[3] = {1, 1, 1};
  std::vector<Index> start_, order_;
};

}  // namespace ballista
