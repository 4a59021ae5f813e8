#include "mpm/grid_contact.hpp"

#include <algorithm>

namespace ballista {

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
    const Vec3 vcm = (1.0 / mtot) * ptot;
    // Corrections use the velocities before any field at this node was corrected.
    for (int f = 0; f < nf; ++f) {
      const Index k = f * nn + i;
      const double m = g.mass[k];
      if (!(m > tiny_mass)) continue;
      // Normal out of field f towards the others: f's outward vector minus the others'.
      Vec3 n = 2.0 * g.grad[k] - gtot;
      const double nlen = norm(n);
      if (!(nlen > 0.0)) continue;
      n = (1.0 / nlen) * n;
      const Vec3 dv = vel[k] - vcm;
      const double dvn = dot(dv, n);
      if (!(dvn > 0.0)) continue;  // separating or sliding: free (Bardenhagen et al. 2000)
      // Friction with the heaviest other field at the node.
      int other = -1;
      double mo = 0.0;
      for (int j = 0; j < nf; ++j)
        if (j != f && g.mass[j * nn + i] > mo) { mo = g.mass[j * nn + i]; other = j; }
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
