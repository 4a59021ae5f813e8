#pragma once
// Exact solution of linear Drucker-Prager plasticity (no hardening, non-associative flow) on
// triaxial paths, sigma22 = sigma33, diagonal strain: verification CATALOGUE A3 (thesis seed 000
// §4.1.1.3, eq. 4.2-4.4, Fig. 4.8-4.9; Brannon & Leelavanichkul, Int. J. Fract. 163 (2010)
// 133-149), and the published analytic stresses of that test.
//
// Surface (geomodel contract, notes4/geomodel_spec.md; tension positive, I1 = tr sigma,
// J2 = s:s/2):  f = sqrt(J2) - FSLOPE (PEAKI1 - I1) <= 0. Thesis eq. 4.2-4.4 (Brannon's
// r/r0 + z/z0 = 1 with r = sqrt(2 J2), z = I1/sqrt(3)) is the same surface with
// FSLOPE = r0/(sqrt(6) z0), PEAKI1 = sqrt(3) z0.
// Flow (contract, "flow_beta"): the deviatoric part of the normal plus beta times its isotropic
// part, M = s/(2 sqrt(J2)) + beta FSLOPE I.
//
// Reduction to two scalars. With diagonal strain increments d11, d22 = d33 the stress keeps
// sigma22 = sigma33: write I1 and q = sigma11 - sigma22 (sqrt(J2) = |q|/sqrt(3)). Hypoelastic
// (thesis seed 000 §2.3) with constant K, G:
//   elastic   dI1 = 3K (d11 + 2 d22),   dq = 2G (d11 - d22)
//   plastic   d eps^p_v = 3 beta FSLOPE dl,   d eps^p_11 - d eps^p_22 = (sqrt(3)/2) sign(q) dl
//   consistency on the (flat) cone, sign(q) constant:
//             dl = (2G sign(q) (d11 - d22)/sqrt(3) + 3K FSLOPE (d11 + 2 d22)) / (G + 9 K beta FSLOPE^2).
// Every relation is linear while sign(q) is fixed and the stress is off the vertex, so an
// increment split into its elastic part (up to f = 0, closed form) and its plastic part is
// integrated exactly, whatever its size: the solution is exact for the logarithmic-strain path
// handed in (strain measure: e_ii = ln F_ii; exact for diagonal F with fixed axes).
#include <array>
#include <vector>

namespace ballista {

struct DruckerPragerParams {
  double bulk = 0.0;     ///< K, Pa
  double shear = 0.0;    ///< G, Pa
  double peak_i1 = 0.0;  ///< PEAKI1, Pa
  double fslope = 0.0;   ///< FSLOPE
  double beta = 1.0;     ///< non-associativity (1: associative)
  /// Limit function Ff(I1) = FSLOPE (PEAKI1 - I1): the largest sqrt(J2) at I1.
  double limit(double i1) const { return fslope * (peak_i1 - i1); }
};

/// The triaxial exact integrator (see the header comment).
class DruckerPragerTriaxial {
 public:
  explicit DruckerPragerTriaxial(const DruckerPragerParams& p);
  /// Advances by log-strain increments d11 and d22 = d33 (exact for any size while the stress
  /// stays off the vertex and q keeps its sign on the surface; throws Error otherwise).
  void advance(double d11, double d22);
  double i1() const { return i1_; }
  double q() const { return q_; }
  double sigma11() const { return i1_ / 3.0 + 2.0 * q_ / 3.0; }
  double sigma22() const { return i1_ / 3.0 - q_ / 3.0; }
  double sqrt_j2() const;
  /// f = sqrt(J2) - Ff(I1) (<= 0 admissible).
  double yield_function() const;
  bool plastic() const { return plastic_; }  ///< last advance ended with plastic flow

 private:
  DruckerPragerParams p_;
  double i1_ = 0.0, q_ = 0.0;
  bool plastic_ = false;
};

/// CATALOGUE A3 (Brannon & Leelavanichkul 2010; Uintah Arenisca test 02, input
/// AreniscaTest_02_VertexTreatment.ups and AreniscaTestSuite_PostProc.py test02): constants, the
/// F table and the published analytic stresses.
struct A3Reference {
  static constexpr double kBulk = 10000.0;   ///< Pa (numbers used as given)
  static constexpr double kShear = 3750.0;   ///< Pa
  static constexpr double kR0 = 50.0;        ///< Brannon's r0, Pa
  static double z0();                        ///< 50 sqrt(3), Pa
  static double peak_i1();                   ///< sqrt(3) z0 = 150 Pa (thesis eq. 4.4)
  static double fslope();                    ///< r0/(sqrt(6) z0) = 0.2357... (thesis eq. 4.4)
  /// Non-associativity the published solution needs: 1/2. The dwell of leg 1.5-2 (thesis §4.1.1.3:
  /// "alignment of the trial-stress rate with the return projection direction P") requires the
  /// strain rate to be parallel to M, i.e. (d11 + 2 d22)/(d11 - d22) = -2 sqrt(3) beta FSLOPE;
  /// the table's leg has ln-strain ratio -1/sqrt(6) = -2 sqrt(3) (1/2) FSLOPE. (Uintah's input runs
  /// Arenisca3 with BETA_nonassociativity = 0.353553 in that model's own normalisation.) With
  /// beta = 1 the stress would not dwell: sigma11(t = 2) = -417.1 Pa instead of -313.3 Pa.
  static constexpr double kBeta = 0.5;
  static DruckerPragerParams params();
  /// Table rows t, F11, F22 = F33 (diagonal F, linear interpolation in time).
  static const std::array<double, 6>& t();
  static const std::array<double, 6>& F11();
  static const std::array<double, 6>& F22();
  /// Published stresses at the rows (Pa).
  static const std::array<double, 6>& sigma11();
  static const std::array<double, 6>& sigma22();
};

}  // namespace ballista
