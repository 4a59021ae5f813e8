#include "otm/otm_fbar.hpp"

#include <algorithm>
#include <cmath>

#include "core/parallel.hpp"

namespace ballista::otm {

namespace {

/// det of the in-plane block (plane strain) or of the whole tensor.
double volume_ratio(const Mat3& dF, bool plane) {
  return plane ? dF(0, 0) * dF(1, 1) - dF(0, 1) * dF(1, 0) : det(dF);
}

/// s times the in-plane rows (plane strain) or times every row.
void scale(Mat3& A, double s, bool plane) {
  const int rows = plane ? 2 : 3;
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < 3; ++j) A(i, j) *= s;
}

}  // namespace

void NodalFBar::apply(const Supports& sup, Index node_count, bool plane, double dt, const FBarFields& f,
                      const Communicator& comm) {
  const Index n = f.count;
  dj_.resize(static_cast<std::size_t>(n));
  vn_.resize(static_cast<std::size_t>(n));
  for_each(0, n, [&](Index p) {
    dj_[p] = volume_ratio(Mat3::identity() + dt * f.L[p], plane);
    vn_[p] = f.volume[p] / dj_[p];
  });
  w_.assign(static_cast<std::size_t>(node_count), 0.0);
  theta_.assign(static_cast<std::size_t>(node_count), 0.0);
  for (Index p = 0; p < n; ++p)
    for (Index k = sup.offset[p]; k < sup.offset[p + 1]; ++k) {
      const Index a = sup.node[k];
      const double wv = sup.N[k] * vn_[p];
      w_[a] += wv;
      theta_[a] += wv * dj_[p];
    }
  if (comm.distributed()) {
    std::vector<double> both(w_);
    both.insert(both.end(), theta_.begin(), theta_.end());
    comm.sum_in_rank_order(both.data(), both.size());
    std::copy(both.begin(), both.begin() + node_count, w_.begin());
    std::copy(both.begin() + node_count, both.end(), theta_.begin());
  }
  for_each(0, node_count, [&](Index a) {
    if (w_[a] > 0.0) theta_[a] /= w_[a];
  });
  const double m = plane ? 2.0 : 3.0;
  for_each(0, n, [&](Index p) {
    double bar = 0.0;
    for (Index k = sup.offset[p]; k < sup.offset[p + 1]; ++k) bar += sup.N[k] * theta_[sup.node[k]];
    const double s = std::pow(bar / dj_[p], 1.0 / m);
    Mat3 dF = Mat3::identity() + dt * f.L[p];
    scale(dF, s, plane);
    f.L[p] = (1.0 / dt) * (dF - Mat3::identity());
    scale(f.F[p], s, plane);
    f.volume[p] = f.volume0[p] * det(f.F[p]);
    if (f.extent) scale(f.extent[p], s, plane);
    if (f.Fr) scale(f.Fr[p], s, plane);
  });
}

}  // namespace ballista::otm
