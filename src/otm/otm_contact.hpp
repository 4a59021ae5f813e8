#pragma once
// Contact between OTM bodies: a penalty between the material points of different bodies, the
// pinball method of Belytschko & Neal (IJNME 31 (1991) 547) with the material points as pinballs.
//
// Each body has its own nodes (otm.nodes: per_body), so without this the bodies pass through each
// other. Point p is a ball of radius a_p, half the edge of the cube (square) of its current volume:
//   a_p = V_p^(1/3) / 2 (3D),  sqrt(V_p) / 2 (plane strain, V per unit thickness),
//   sqrt(V_p / r_p) / 2 (axisymmetric, V per radian = area times r_p),
// so two lattices that touch (points half a spacing from the interface on either side) are just in
// contact, and a compressed point's ball shrinks with it. Two points of different bodies closer
// than a_p + a_q repel along the line of their centres (frictionless) with
//   f_pq = k_pq (a_p + a_q - |x_p - x_q|) n_pq,  k_pq = (penalty / 2) min(m_p w_p^2, m_q w_q^2),
// w_p^2 the largest stiffness bound omega_a^2 of p's support nodes (the solver's stable step): the
// spring is as stiff as the material around the stiffer-bound side's point allows, so, as for the
// penalty walls, it does not depend on the time step and raises a node's omega^2 by at most about
// the factor 1 + penalty (the stable step takes that factor). The force on q is exactly -f_pq, so
// linear momentum is conserved; each point's force goes to its nodes with N_a(x_p), as an external
// force would (Algorithm 1 line 9), and the work of the node forces is booked as contact work.
#include <cstdint>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista::otm {

struct ContactGeometry {
  int dim = 3;          ///< axes of the motion: 3, or 2 (plane strain, axisymmetric)
  bool axisym = false;  ///< volumes per radian (radius from V / r)
};

/// The pinball radius a_p of a point of volume V at radial position r (axisymmetric), m.
double pinball_radius(double volume, double r, const ContactGeometry& g);

/// The contact force on every point (f[p], N; per radian or per unit thickness as the volumes are)
/// from every pair of points of different `body` whose balls overlap. `stiffness[p]` is m_p w_p^2
/// (N/m). Returns the number of pairs in contact. Deterministic: each point sums its partners in a
/// fixed order, whatever the thread count.
Index pinball_forces(const Vec3* x, const double* volume, const std::int64_t* body, const double* stiffness, Index n,
                     double penalty, const ContactGeometry& g, std::vector<Vec3>& f);

}  // namespace ballista::otm
