#pragma once
// Generalized vortex manufactured solution (Kamojjala, Brannon, Sadeghirad & Guilkey, "Verification
// tests in solid mechanics", Engineering with Computers 31 (2015) 193-213; Uintah
// src/CCA/Components/MPM/MMS/MMS.cc "GeneralizedVortex" and inputs/MPM/GenVortex.ups;
// verification CATALOGUE B2). An annulus 0.75 <= R <= 1.25 about the z axis, plane strain, of
// compressible neo-Hookean material sigma = [lambda ln J I + mu (F F^T - I)] / J; each ring of
// reference radius R rotates rigidly about the axis by
//   alpha(R, t) = A sin(c pi t) h(R),   h(R) = 1 - 32 (R - 1)^2 + 256 (R - 1)^4 = ((4R-3)(4R-5))^2.
// h and h' vanish at both radii, so the faces stay traction free; at t = 0 the body is undeformed
// and spins with v = R alpha_t e_theta.
// Every function takes the reference position X (only X_0, X_1 are used) and time t.
//
// Derivation of the body force (checked against finite differences in
// tests/unit/points/test_mms_generalized_vortex.cpp). With r = R, theta = Theta + alpha and
// gamma = R d alpha/dR, F = e_r (x) E_R + e_theta (x) E_Theta + gamma e_theta (x) E_R (det F = 1),
// so in the current polar basis B = F F^T = [[1, gamma], [gamma, 1 + gamma^2]] and, with J = 1,
// sigma = mu (B - I): sigma_rr = 0, sigma_rt = mu gamma, sigma_tt = mu gamma^2 (lambda drops out).
// The polar divergence (no theta dependence) is
//   (div sigma)_r = -mu gamma^2 / R,   (div sigma)_t = mu (gamma' + 2 gamma / R) = mu (3 alpha' + R alpha''),
// the acceleration of x = R e_r(theta) is a = -R alpha_t^2 e_r + R alpha_tt e_theta, and
// b = a - div(sigma) / rho (rho = rho0):
//   b_r = -R alpha_t^2 + (mu / rho0) R alpha_R^2,
//   b_t =  R alpha_tt  - (mu / rho0) (3 alpha_R + R alpha_RR),
// rotated to Cartesian by the current angle Theta + alpha. This is the expression of Uintah's
// MMS.cc (br, bt there, written with (4R-3)(4R-5) factored out); it holds for this neo-Hookean
// form only (a deviatoric form mu J^(-5/3) dev(B) would add a pressure mu gamma^2 / 3).
#include <cmath>
#include <numbers>

#include "core/tensor.hpp"

namespace ballista::mms {

struct GeneralizedVortex {
  double mu = 384.615;   ///< shear modulus, Pa (CATALOGUE B2; Uintah GenVortex.ups)
  double K = 833.333;    ///< bulk modulus, Pa
  double rho0 = 1000.0;  ///< kg/m^3
  double A = 1.0;        ///< amplitude of the rotation, rad
  double c = 1.0;        ///< frequency factor, 1/s: alpha ~ sin(c pi t)
  double R_inner = 0.75; ///< m
  double R_outer = 1.25; ///< m

  double lambda() const { return K - 2.0 * mu / 3.0; }

  /// h(R) and its first two derivatives.
  static double h(double R) {
    const double s = R - 1.0;
    return 1.0 - 32.0 * s * s + 256.0 * s * s * s * s;
  }
  static double dh(double R) {
    const double s = R - 1.0;
    return -64.0 * s + 1024.0 * s * s * s;
  }
  static double d2h(double R) {
    const double s = R - 1.0;
    return -64.0 + 3072.0 * s * s;
  }

  /// alpha and its derivatives in time (t, tt) and radius (R, RR).
  struct Angle {
    double a, a_t, a_tt, a_R, a_RR;
  };
  Angle angle(double R, double t) const {
    using std::numbers::pi;
    const double s = std::sin(c * pi * t), co = std::cos(c * pi * t);
    return {A * s * h(R), A * c * pi * co * h(R), -A * c * c * pi * pi * s * h(R), A * s * dh(R),
            A * s * d2h(R)};
  }

  static double radius(const Vec3& X) { return std::hypot(X[0], X[1]); }

  /// Current position x = Q(alpha) X (rotation about z).
  Vec3 position(const Vec3& X, double t) const {
    const double al = angle(radius(X), t).a;
    const double ca = std::cos(al), sa = std::sin(al);
    return {{ca * X[0] - sa * X[1], sa * X[0] + ca * X[1], X[2]}};
  }
  Vec3 displacement(const Vec3& X, double t) const { return position(X, t) - X; }

  /// v = R alpha_t e_theta = alpha_t (e_z x x).
  Vec3 velocity(const Vec3& X, double t) const {
    const Vec3 x = position(X, t);
    const double at = angle(radius(X), t).a_t;
    return {{-at * x[1], at * x[0], 0.0}};
  }

  /// F = Q(alpha) (I + R alpha_R E_Theta (x) E_R) in Cartesian components (header comment).
  Mat3 F(const Vec3& X, double t) const {
    const double R = radius(X);
    const Angle g = angle(R, t);
    const double ca = std::cos(g.a), sa = std::sin(g.a);
    Mat3 Q = Mat3::identity();
    Q(0, 0) = ca; Q(0, 1) = -sa;
    Q(1, 0) = sa; Q(1, 1) = ca;
    Mat3 shear = Mat3::identity();
    if (R > 0.0) {
      // R alpha_R E_Theta (x) E_R with E_R = X / R, E_Theta = (-X_1, X_0) / R.
      const double er[2] = {X[0] / R, X[1] / R}, et[2] = {-X[1] / R, X[0] / R};
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) shear(i, j) += R * g.a_R * et[i] * er[j];
    }
    return Q * shear;
  }

  /// Body force per unit mass (header comment; Kamojjala et al. 2015, Uintah MMS.cc).
  Vec3 body_force(const Vec3& X, double t) const {
    const double R = radius(X);
    const Angle g = angle(R, t);
    const double m = mu / rho0;
    const double br = -R * g.a_t * g.a_t + m * R * g.a_R * g.a_R;
    const double bt = R * g.a_tt - m * (3.0 * g.a_R + R * g.a_RR);
    const double beta = std::atan2(X[1], X[0]) + g.a;  // current polar angle
    const double cb = std::cos(beta), sb = std::sin(beta);
    return {{cb * br - sb * bt, sb * br + cb * bt, 0.0}};
  }
};

}  // namespace ballista::mms
