#include "mpm/grid_contact.hpp"

#include <algorithm>
#include <vector>

namespace ballista {

namespace {

// Most sweeps over the pairs of a node where three or more fields meet: a pair settled in one
// sweep can approach again when a later pair moves one of its fields, and each sweep removes
// kinetic energy, so a few sweeps leave what approaches small; a bound keeps the cost fixed.
constexpr int kPairSweeps = 8;

// Contact at a node where three or more fields have mass, as a sequence of two-body collisions.
// Against the centre of mass each field would take its own normal, and the corrections of three
// fields need not cancel: three unit masses with outward vectors (1,0,0), (-1,0,0), (0,1,0) and
// velocities (1,0,0), (-1,0,0), 0 would gain (0, 0.8, 0) kg m/s. Here each approaching pair (a, b)
// takes the impulse of a perfectly inelastic collision of the two along its own normal,
// n_ab = unit(g_a - g_b) (the normal apply_grid_contact gives two fields, so at a node of two
// fields this would be its correction in exact arithmetic), with reduced mass m_a m_b / (m_a + m_b) and
// Coulomb friction on the tangential relative velocity capped at sticking (Bardenhagen et al.
// 2001), equal and opposite on the two: the node's momentum is kept to round-off and every
// impulse removes kinetic energy. Pairs are swept in a fixed order (deterministic) until none
// approaches or kPairSweeps sweeps are done. Returns the work of the corrections and its friction
// part: the kinetic-energy change of the fields at the node.
ContactWork resolve_pairs(const FieldGrid& g, Index i, Vec3* vel, double tiny_mass, Vec3* impulse,
                          Vec3* friction_impulse) {
  const int nf = g.fields;
  const Index nn = g.nodes;
  // Such nodes are few (where three bodies meet), so small vectors here cost nothing measurable.
  std::vector<int> idx;
  std::vector<Vec3> v0;
  for (int f = 0; f < nf; ++f)
    if (g.mass[f * nn + i] > tiny_mass) {
      idx.push_back(f);
      v0.push_back(vel[f * nn + i]);
    }
  const int np = static_cast<int>(idx.size());
  std::vector<Vec3> ct_sum(idx.size());
  for (int sweep = 0; sweep < kPairSweeps; ++sweep) {
    bool any = false;
    for (int a = 0; a < np; ++a)
      for (int b = a + 1; b < np; ++b) {
        const Index ka = idx[a] * nn + i, kb = idx[b] * nn + i;
        Vec3 n = g.grad[ka] - g.grad[kb];
        const double nlen = norm(n);
        if (!(nlen > 0.0)) continue;
        n = (1.0 / nlen) * n;
        const Vec3 dv = vel[ka] - vel[kb];
        const double dvn = dot(dv, n);
        if (!(dvn > 0.0)) continue;
        any = true;
        const double ma = g.mass[ka], mb = g.mass[kb];
        const double mred = ma * mb / (ma + mb);
        const double mu = g.friction[idx[a] * nf + idx[b]];
        const Vec3 dvt = dv - dvn * n;
        const double vt = norm(dvt);
        const double mup = vt > 0.0 ? std::min(mu, vt / dvn) : 0.0;
        Vec3 jt;  // tangential impulse on a, N s
        if (mup > 0.0) jt = -(mred * mup * dvn / vt) * dvt;
        const Vec3 j = -(mred * dvn) * n + jt;  // impulse on a; b takes -j
        vel[ka] += (1.0 / ma) * j;
        vel[kb] = vel[kb] - (1.0 / mb) * j;
        ct_sum[a] += (1.0 / ma) * jt;
        ct_sum[b] = ct_sum[b] - (1.0 / mb) * jt;
      }
    if (!any) break;
  }
  ContactWork work;
  for (int a = 0; a < np; ++a) {
    const Index k = idx[a] * nn + i;
    const double m = g.mass[k];
    const Vec3 c = vel[k] - v0[a];
    const Vec3 vmid = 0.5 * (v0[a] + vel[k]);
    work.total += m * dot(c, vmid);
    work.friction += m * dot(ct_sum[a], vmid);
    if (impulse) {
      impulse[k] += c;
      friction_impulse[k] += ct_sum[a];
    }
  }
  return work;
}

}  // namespace

ContactWork apply_grid_contact(const FieldGrid& g, Vec3* vel, double tiny_mass, Vec3* impulse, Vec3* friction_impulse) {
  const int nf = g.fields;
  const Index nn = g.nodes;
  double w[2];
  deterministic_sum<2>(0, nn, [&](Index i, double* o) {
    int present = 0;
    double mtot = 0.0;
    Vec3 ptot, gtot;
    for (int f = 0; f < nf; ++f) {
      const Index k = f * nn + i;
      const double m = g.mass[k];
      if (!(m > tiny_mass)) continue;
      ++present;
      mtot += m;
      ptot += m * vel[k];
      gtot += g.grad[k];
    }
    if (present < 2) return;
    if (g.volume) {
      // Gap check: particles of two bodies share a node while a gap of most of a cell lies
      // between them (a GIMP point reaches nodes up to 1.5 cells away); together they then fill
      // little of the node's volume. A correction there moves a body by what a node it barely
      // reaches says: weight w gives a point mass w m_p at the node but a velocity gradient of
      // order sqrt(w) / h from it. Uintah's friction contact has the same test (its
      // volume_constraint on the nodal volumes).
      double filled = 0.0;
      for (int f = 0; f < nf; ++f) filled += g.volume[f * nn + i];
      if (filled < g.min_volume_fraction * g.geom->node_volume(i, g.axisymmetric)) return;
    }
    if (present > 2) {
      const ContactWork wk = resolve_pairs(g, i, vel, tiny_mass, impulse, friction_impulse);
      if (!g.counted || g.counted[i]) {
        o[0] += wk.total;
        o[1] += wk.friction;
      }
      return;
    }
    // Two fields: each against their centre of mass, the two normals opposite, so the two
    // corrections cancel. Corrections use the velocities before either was corrected.
    const Vec3 vcm = (1.0 / mtot) * ptot;
    for (int f = 0; f < nf; ++f) {
      const Index k = f * nn + i;
      const double m = g.mass[k];
      if (!(m > tiny_mass)) continue;
      // Normal out of field f towards the other: f's outward vector minus the other's.
      Vec3 n = 2.0 * g.grad[k] - gtot;
      const double nlen = norm(n);
      if (!(nlen > 0.0)) continue;
      n = (1.0 / nlen) * n;
      const Vec3 dv = vel[k] - vcm;
      const double dvn = dot(dv, n);
      if (!(dvn > 0.0)) continue;  // separating or sliding: free (Bardenhagen et al. 2000)
      int other = 0;  // the other field at the node
      while (other == f || !(g.mass[other * nn + i] > tiny_mass)) ++other;
      const double mu = g.friction[f * nf + other];
      const Vec3 dvt = dv - dvn * n;
      const double vt = norm(dvt);
      // Coulomb: the tangential change is mu times the normal one, but never more than stops the
      // sliding (Bardenhagen et al. 2001: mu' = min(mu, |dv x n| / dv.n)).
      const double mup = vt > 0.0 ? std::min(mu, vt / dvn) : 0.0;
      Vec3 ct;
      if (mup > 0.0) ct = -(mup * dvn / vt) * dvt;
      const Vec3 c = -dvn * n + ct;
      const Vec3 vnew = vel[k] + c;
      // Work of the impulse m c in this pass: the kinetic-energy change of the correction.
      const Vec3 vmid = 0.5 * (vel[k] + vnew);
      if (!g.counted || g.counted[i]) {
        o[0] += m * dot(c, vmid);
        o[1] += m * dot(ct, vmid);
      }
      vel[k] = vnew;
      if (impulse) {
        impulse[k] += c;
        friction_impulse[k] += ct;
      }
    }
  }, w);
  return {w[0], w[1]};
}

}  // namespace ballista
