#pragma once
// The linear peridynamic solid (LPS), an ordinary state-based model (Silling, Epton, Weckner, Xu &
// Askari, J. Elasticity 88 (2007) 151, sec. 15; the discrete form of Peridigm's elastic model,
// Mitchell, SAND2011-8064, and LAMMPS's peri/lps): the force of a bond depends on the deformation
// of both ends' whole families, so the solid takes the bulk modulus K and the shear modulus mu of
// its material (any Poisson's ratio), where a bond-based spring fixes nu = 1/4 in 3D.
// With influence function omega = 1, per point i over its intact bonds j (e = |y| - |xi| the
// extension, y the deformed bond, beta the partial volume, V the reference volume):
//   m_i     = sum_j |xi|^2 beta V_j   over the reference family: the weighted volume (fixed)
//   theta_i = (3 / m_i) sum_j |xi| e beta V_j                    dilatation
//   e^d     = e - theta_i |xi| / 3                                deviatoric extension
//   W_i     = K theta_i^2 / 2 + (15 mu / (2 m_i)) sum_j (e^d)^2 beta V_j   energy density
//   f_i     = sum_j (t_ij + t_ji) (y / |y|) beta V_i V_j          force (N)
// with the force state t_ij = d(W_i V_i)/d(e_ij) / (beta V_i V_j), so that the forces are the
// gradient of the energy whatever the bonds broken:
//   t_ij = (3 K theta_i / m_i) |xi| + (15 mu / m_i) (e^d - |xi| S_i / m_i),
//   S_i  = sum_j e^d |xi| beta V_j = theta_i (m_i - m_i,intact) / 3.
// With every bond intact S_i = 0 and t_ij is the LPS force state of Silling et al. (2007, sec. 15):
// a uniform dilatation eps gives theta = 3 eps and W = 9 K eps^2 / 2 at every point whatever its
// family, and a uniform shear W = 2 mu eps_xy^2 up to the lattice's quadrature of the horizon
// sphere (tests/unit/peridynamics/test_lps.cpp). S_i keeps the energy audit closed once bonds
// break (m_i is not renormalised over the intact bonds: a point left with one bond would carry its
// whole volume's dilatation on it, and the stable step would collapse with its m).
// Per point the pass keeps B_i = 3 K theta_i / m_i - (15 mu / m_i)(theta_i / 3 + S_i / m_i), so
// that t_ij = B_i |xi| + (15 mu / m_i) e.
//
// Two passes over each own point's whole row (each writes only its own point and its own row, so
// the results do not depend on the thread count or, with the ghosts' B from their owners, on
// the ranks): the dilatation with the failures, then the forces. A bond breaks when its stretch
// passes min(s0_i, s0_j), which both ends compute alike; it is marked kBreaking for the step in
// which it breaks. Its ends' energy then changes from W_old (the bond intact, theta_old) to W_new at
// the same positions. As the bond-based pass books a breaking bond's trapezoidal work over the step
// (velocity Verlet gave the points only the first half-kick of the old forces), a point books
//   D_i = (W_old_i - W_new_i) V_i + (f_old_i - f_new_i) . (x_i - x_prev_i) / 2,
// where f_old is its force with the breaking bonds intact (computed only for the points near a break).
#include <cstdint>

#include "core/parallel.hpp"

namespace ballista::pd {

/// Broken flag of a bond in the evaluation that breaks it (1 afterwards).
inline constexpr std::uint8_t kBreaking = 2;

struct LpsPassArgs {
  const double* x;              ///< positions, 3 per local point, m
  const double* x_prev;         ///< positions at the step's start, 3 per local point, m
  const double* vol0;           ///< reference volumes, m^3
  const std::int64_t* material; ///< material of each local point
  const double* bulk;           ///< K per material, Pa
  const double* shear;          ///< mu per material, Pa
  const double* m;              ///< weighted volume per local point, m^5 (0: no bonds)
  const double* s0;             ///< critical stretch per local point
  double alpha;                 ///< s0 = s00 - alpha s_min
  const double* length0;        ///< |xi| per bond, m
  const double* inv_length0;    ///< 1/|xi| per bond, 1/m
  const float* beta;            ///< partial-volume factor per bond
  const std::int32_t* other;    ///< other end per bond
  const std::int32_t* mirror;   ///< the bond's position in the other end's row
  const Index* offset;          ///< row starts
  const std::uint8_t* ghost;    ///< 1 for a ghost copy
  std::uint8_t* broken;         ///< per bond: 0 intact, kBreaking, 1 broken
  // Contact of the ends of broken bonds (as bond_pass.hpp): c_s = cs_over_c c per material pair.
  bool contact;
  const double* micromodulus;   ///< c per material pair (nmat x nmat), N/m^6
  int nmat;
  double cs_over_c;             ///< 1/m
  double range;                 ///< m
  // Per local point.
  double* theta;                ///< dilatation with this evaluation's failures
  double* theta_old;            ///< dilatation before them
  double* coef;                 ///< B of the force state with this evaluation's failures, Pa/m^5
  double* coef_old;             ///< B before them
  double* breaks;               ///< 1 if one of the point's bonds breaks in this evaluation, else 0
  double* f;                    ///< force, 3 per point, N
  double* energy;               ///< strain energy W_i V_i, J
  double* dissipated;           ///< this evaluation's dissipation, J
  double* vol_broken;           ///< sum of beta V over broken bonds, m^3
  double* smax;                 ///< max of -alpha s over intact bonds
  double* e_contact;            ///< contact-spring energy (each end its half), J
  double* k_contact;            ///< sum of c_s V_other over active contacts, N/m^4
};

/// The weighted volume m_p of local points [p0, p1) over their reference rows.
void lps_weighted_volume(const LpsPassArgs& a, Index p0, Index p1, double* m);

/// Pass 1 for the own local point p: stretches, failures (broken[k] = kBreaking at both copies of
/// the bond this rank holds), theta, theta_old, coef, coef_old, breaks, vol_broken and smax at p.
void lps_dilatation(const LpsPassArgs& a, Index p);

/// Pass 2 for the own local point p, once every local point's coef (and, where a bond broke,
/// coef_old and breaks) is known: force, energy, dissipation, contact of broken bonds.
void lps_forces(const LpsPassArgs& a, Index p);

}  // namespace ballista::pd
