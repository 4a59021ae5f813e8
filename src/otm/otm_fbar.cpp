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
                      const NodeFoldScope* nodes) {
  const Index n = f.count;
  dj_.resize(static_cast<std::size_t>(n));
  vn_.resize(static_cast<std::size_t>(n));
  for_each(0, n, [&](Index p) {
    dj_[p] = volume_ratio(Mat3::identity() + dt * f.L[p], plane);
    vn_[p] = f.volume[p] / dj_[p];
  });
  // The nodal sums, folded over each node's points in point order (bitwise on any rank count).
  NodeFoldScope scope;
  if (nodes) {
    scope = *nodes;
  } else {
    build_influences(sup, node_count, inf_);
    scope.inf = &inf_;
    scope.nodes = node_count;
  }
  const Influences& inf = *scope.inf;
  struct In {
    double N, vn, dj;
  };
  struct Acc {
    double w, theta;
  };
  std::vector<Acc> sums;
  fold_nodes<Acc, In>(
      scope, sums, [](Index) { return true; },
      [&](Index i, In& in) {
        const Index p = inf.owner[i];
        in = In{sup.N[inf.entry[i]], vn_[p], dj_[p]};
        return true;
      },
      [](Acc& acc, const In& in) {
        add_product(acc.w, in.N, in.vn);
        add_product(acc.theta, in.N * in.vn, in.dj);
      });
  theta_.resize(static_cast<std::size_t>(node_count));
  for_each(0, node_count, [&](Index a) {
    const Acc& s = sums[static_cast<std::size_t>(a)];
    theta_[a] = s.w > 0.0 ? s.theta / s.w : s.theta;
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
