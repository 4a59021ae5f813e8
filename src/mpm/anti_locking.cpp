#include "mpm/anti_locking.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "core/error.hpp"
#include "core/parallel.hpp"

namespace ballista {

namespace {
constexpr AntiLocking kAllKinds[] = {AntiLocking::None, AntiLocking::FBar};

const char* anti_locking_name(AntiLocking a) { return a == AntiLocking::FBar ? "fbar" : "none"; }
}  // namespace

std::vector<std::string> anti_locking_names() {
  std::vector<std::string> names;
  for (AntiLocking a : kAllKinds) names.emplace_back(anti_locking_name(a));
  return names;
}

AntiLocking parse_anti_locking(const std::string& name) {
  std::string lower(name);
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (AntiLocking a : kAllKinds)
    if (lower == anti_locking_name(a)) return a;
  throw Error("unknown anti_locking '" + name + "'; valid names: none, fbar");
}

void CellFBar::clear_slots(Index n, bool across_ranks) {
  if (across_ranks) {
    std::fill(v_new_.begin(), v_new_.end(), 0.0);
    std::fill(v_old_.begin(), v_old_.end(), 0.0);
    return;
  }
  for (Index p = 0; p < n; ++p) v_new_[cell_[p]] = v_old_[cell_[p]] = 0.0;
}

namespace {
/// The (cell, material) slot of a point at x: the node index of its cell's lowest corner (the cell
/// clamped into the block like the solver's sort; with patches of k cells per axis, the patch's
/// lowest cell) times the material count, plus its material.
inline Index slot_of(const GridGeometry& g, const Vec3& x, const std::int64_t* material, int nmat, int patch,
                     Index p) {
  int c[3] = {0, 0, 0};
  for (int a = 0; a < g.dim; ++a) {
    c[a] = std::clamp(g.cell_of(x[a], a), 0, g.nodes[a] - 1);
    c[a] -= c[a] % patch;
  }
  return g.node_index(c[0], c[1], c[2]) * nmat + (material ? material[p] : 0);
}
}  // namespace

int CellFBar::prepare(const GridGeometry& g, const std::int64_t* material, int materials, Index n) {
  const int nmat = material ? materials : 1;
  const size_t slots = static_cast<size_t>(g.node_count()) * static_cast<size_t>(nmat);
  if (v_new_.size() != slots) {
    v_new_.assign(slots, 0.0);
    v_old_.assign(slots, 0.0);
  }
  cell_.resize(n);
  return nmat;
}

void CellFBar::apply(const GridGeometry& g, Dimension dimension, double dt, const FBarPoints& pts,
                     const FBarSlotSum& across_ranks) {
  const Index n = pts.count;
  if (!(dt > 0.0) || (n == 0 && !across_ranks)) return;  // a rank without points still takes part
  const int nmat = prepare(g, pts.material, pts.materials, n);
  v_old_p_.resize(n);
  const Mat3 I = Mat3::identity();
  // 1. Per point: its (cell, material) slot and its volume at t_n, V_p^n = V_p^{n+1} / dJ_p,
  // dJ_p = det dF_p.
  for_each(0, n, [&](Index p) {
    cell_[p] = slot_of(g, pts.x[p], pts.material, nmat, patch_, p);
    v_old_p_[p] = pts.volume[p] / det(I + dt * pts.L[p]);
  });
  // 2. Per (cell, material): V_c^{n+1} and V_c^n, summed in point order by one thread (the sums,
  // and so the result, do not depend on the thread count). Only the slots that hold points are
  // cleared.
  double* vn = v_new_.data();
  double* vo = v_old_.data();
  clear_slots(n, static_cast<bool>(across_ranks));
  for (Index p = 0; p < n; ++p) {
    vn[cell_[p]] += pts.volume[p];
    vo[cell_[p]] += v_old_p_[p];
  }
  if (across_ranks) across_ranks(vn, vo, nmat);
  // 3. Per point: dFbar = s dF with s = (dJbar_c / dJ_p)^(1/m) on the deforming axes (Coombs et
  // al. 2018); F_{n+1} = dFbar F_n = S F_{n+1}, S = diag(s, s, s) or diag(s, s, 1) in plane
  // strain (F and dF have no in-plane/out-of-plane coupling there); Lbar = (S dF - I)/dt =
  // S L + (S - I)/dt; V = V_0 det F_{n+1}.
  const int m = dimension == Dimension::PlaneStrain ? 2 : 3;
  const double inv_dt = 1.0 / dt;
  for_each(0, n, [&](Index p) {
    const Index c = cell_[p];
    const double ratio = (vn[c] / vo[c]) * (v_old_p_[p] / pts.volume[p]);  // dJbar_c / dJ_p
    const double s = m == 3 ? std::cbrt(ratio) : std::sqrt(ratio);
    Mat3& F = pts.F[p];
    Mat3& L = pts.L[p];
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < 3; ++j) {
        F(i, j) *= s;
        L(i, j) *= s;
      }
      L(i, i) += (s - 1.0) * inv_dt;
    }
    pts.volume[p] = pts.volume0[p] * det(F);
  });
}

void CellFBar::force_pressure(const GridGeometry& g, const FBarForcePoints& pts, std::vector<double>& out,
                              const FBarSlotSum& across_ranks) {
  const Index n = pts.count;
  out.resize(n);
  if (n == 0 && !across_ranks) return;  // a rank without points still takes part in the exchange
  const int nmat = prepare(g, pts.material, pts.materials, n);
  // 1. Per point: its (cell, material) slot, and its total pressure p + q (in out, for now).
  for_each(0, n, [&](Index p) {
    cell_[p] = slot_of(g, pts.x[p], pts.material, nmat, patch_, p);
    const Mat3& s = pts.stress[p];
    out[p] = -(s(0, 0) + s(1, 1) + s(2, 2)) / 3.0 + (pts.viscous_pressure ? pts.viscous_pressure[p] : 0.0);
  });
  // 2. Per slot: sum V (p + q) and sum V, in point order by one thread (thread-count independent).
  double* vp = v_new_.data();
  double* vv = v_old_.data();
  clear_slots(n, static_cast<bool>(across_ranks));
  for (Index p = 0; p < n; ++p) {
    vp[cell_[p]] += pts.volume[p] * out[p];
    vv[cell_[p]] += pts.volume[p];
  }
  if (across_ranks) across_ranks(vp, vv, nmat);
  // 3. Per point: the isotropic stress to take off sigma_p, P_bar + tr(sigma_p) / 3.
  for_each(0, n, [&](Index p) {
    const Index c = cell_[p];
    const Mat3& s = pts.stress[p];
    out[p] = vp[c] / vv[c] + (s(0, 0) + s(1, 1) + s(2, 2)) / 3.0;
  });
}

}  // namespace ballista
