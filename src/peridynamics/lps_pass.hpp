#pragma once
// The linear peridynamic solid (LPS), an ordinary state-based model (Silling, Epton, Weckner, Xu &
// Askari, J. Elasticity 88 (2007) 151, sec. 15; the discrete form of Peridigm's elastic model and
// LAMMPS's peri/lps), with the plasticity of Mitchell ("A nonlocal, ordinary, state-based
// plasticity model for peridynamics", SAND2011-3166; LAMMPS's peri/eps): the force of a bond
// depends on the deformation of both ends' whole families, so the solid takes the bulk modulus K
// and the shear modulus mu of its material (any Poisson's ratio), where a bond-based spring fixes
// nu = 1/4 in 3D, and yields like von Mises. With influence function omega = 1, per point i over
// its intact bonds j (e = |y| - |xi| the extension, y the deformed bond, beta the partial volume, V
// the reference volume, e^p_ij the plastic deviatoric extension of the bond at end i):
//   m_i     = sum_j |xi|^2 beta V_j   over the reference family: the weighted volume (fixed)
//   theta_i = (3 / m_i) sum_j |xi| e beta V_j                    dilatation
//   e^d     = e - theta_i |xi| / 3                                deviatoric extension
//   t^d_ij  = alpha_i (e^d - e^p_ij),  alpha_i = 15 mu / m_i      deviatoric force state
//   W_i     = K theta_i^2 / 2 + sum_j (t^d_ij)^2 beta V_j / (2 alpha_i)   stored energy density
//   f_i     = sum_j (t_ij + t_ji) (y / |y|) beta V_i V_j          force (N)
// with the force state t_ij = d(W_i V_i)/d(e_ij) / (beta V_i V_j) at fixed e^p, so that the forces
// are the gradient of the energy whatever the bonds broken:
//   t_ij = (3 K theta_i / m_i) |xi| + t^d_ij - alpha_i |xi| S_i / m_i,
//   S_i  = sum_j (e^d - e^p_ij) |xi| beta V_j    (0 for a whole elastic family).
// With every bond intact and no plastic flow t_ij is the LPS force state of Silling et al.: a
// uniform dilatation eps gives theta = 3 eps and W = 9 K eps^2 / 2 at every point whatever its
// family, and a uniform shear W = 2 mu eps_xy^2 up to the lattice's quadrature of the horizon
// sphere (tests/unit/peridynamics/test_lps.cpp). S_i keeps the energy audit closed once bonds
// break (m_i is not renormalised over the intact bonds: a point left with one bond would carry its
// whole volume's dilatation on it, and the stable step would collapse with its m).
// Per point the pass keeps B_i = 3 K theta_i / m_i - alpha_i (theta_i / 3 + S_i / m_i), so that
// t_ij = B_i |xi| + alpha_i (e - e^p_ij).
//
// Plasticity (Mitchell 2011): yield function f = |t^d|^2 / 2 - psi0, |t^d|^2 = sum_j (t^d)^2 beta V,
// perfectly plastic, associative, e^p advanced by backward Euler (radial return): the trial
// t^d = alpha (e^d - e^p_n); if f > 0, t^d is scaled onto |t^d| = sqrt(2 psi0) and
// e^p += dlambda t^d with dlambda = (|t^d_trial| / sqrt(2 psi0) - 1) / alpha. The point dissipates
// the plastic work of the step by the trapezoidal rule, sum (t^d_n + t^d_n+1) de^p beta V V_i / 2:
// with t^d = alpha (e^d - e^p) it is exactly the deviatoric work (t^d_n + t^d_n+1) de^d / 2, the
// rule velocity Verlet's forces do work by, less the change of stored energy, so the audit closes.
// (The backward-Euler work t^d_n+1 . de^p differs by (t^d_n+1 - t^d_n) . de^p / 2: second order in
// a smooth flow, but not in the step after a break, which moves a point's state far beyond yield
// at once: the audit of a tearing plastic ring was then off by 1.7 %.) psi0 matches von Mises: under a uniform deviatoric strain eps^d the continuum
// gives |t^d|^2 = alpha^2 m (2/15) eps^d:eps^d and J2 = 2 mu^2 eps^d:eps^d, so at J2 = sigma_y^2 / 3,
// psi0 = 5 sigma_y^2 / (2 m_i) (25 sigma_y^2 / (8 pi delta^5) with the continuum m = 4 pi delta^5/5).
//
// Two passes, three with plasticity, over each own point's whole row (each writes only its own point and its own row,
// so the results do not depend on the thread count or, with the ghosts' B from their owners, on
// the ranks): the dilatation with the failures (and B); the plastic return (and B); the forces. A bond breaks when
// its stretch passes min(s0_i, s0_j), which both ends compute alike; it is marked kBreaking for
// the evaluation in which it breaks. The return is made with the breaking bonds still in (the
// constitutive update first, then the failures); the ends' energy then changes from W_old (the
// bonds intact, theta_old) to W_new at the same positions and the same e^p. As the bond-based pass books a breaking
// bond's trapezoidal work over the step (velocity Verlet gave the points only the first half-kick
// of the old forces), a point books
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
  const double* alpha_point;    ///< 15 mu / m per local point, Pa/m^5 (0: no bonds)
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
  double* length;               ///< per bond end: |y| of this evaluation (pass 1, for the return), m; null: elastic
  double* plastic;              ///< per bond end: e^p, m (null: elastic)
  double* td_prev;              ///< per bond end: t^d after the last evaluation, N/m^6 (with `plastic`)
  double yield_sq;              ///< sigma_y^2, Pa^2 (with `plastic`)
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
  double* s_elastic;            ///< S without the plastic extensions, with the failures, m^5
  double* s_elastic_old;        ///< the same before them
  double* breaks;               ///< 1 if one of the point's bonds breaks in this evaluation, else 0
  bool any_break;               ///< some bond of some rank breaks in this evaluation (set after pass 1)
  double* f;                    ///< force, 3 per point, N
  double* energy;               ///< stored energy W_i V_i, J
  double* dissipated;           ///< this evaluation's dissipation (plastic flow, breaks), J; zero on entry
  double* vol_broken;           ///< sum of beta V over broken bonds, m^3
  double* smax;                 ///< max of -alpha s over intact bonds
  double* e_contact;            ///< contact-spring energy (each end its half), J
  double* k_contact;            ///< sum of c_s V_other over active contacts, N/m^4
};

/// The weighted volume m_p of local points [p0, p1) over their reference rows.
void lps_weighted_volume(const LpsPassArgs& a, Index p0, Index p1, double* m);
/// The deviatoric stiffness 15 mu / m_p of local points [p0, p1) (a.m set).
void lps_deviatoric_stiffness(const LpsPassArgs& a, Index p0, Index p1, double* alpha);

/// Pass 1 for the own local point p: |y| of its bonds, failures (broken[k] = kBreaking at both
/// copies of the bond this rank holds), theta, theta_old, s_elastic(_old), breaks, vol_broken and
/// smax at p, and coef and coef_old as if no bond end had a plastic extension.
void lps_dilatation(const LpsPassArgs& a, Index p);

/// Pass 2 (with plasticity only) for the own local point p: the plastic return of its bonds' ends
/// (e^p, the plastic dissipation, t^d for the next step), and coef and coef_old with e^p.
void lps_return(const LpsPassArgs& a, Index p);

/// coef and coef_old of p from its theta and s_elastic, less the plastic parts of S,
/// sum e^p |xi| beta V over the intact bonds (and, before the failures, the breaking ones).
void lps_coefficients(const LpsPassArgs& a, Index p, double plastic_sum, double plastic_sum_old);

/// The last pass for the own local point p, once every local point's coef (and, where a bond broke,
/// coef_old and breaks) is known: force, stored energy, the dissipation of a break, contact of
/// broken bonds.
void lps_forces(const LpsPassArgs& a, Index p);

}  // namespace ballista::pd
