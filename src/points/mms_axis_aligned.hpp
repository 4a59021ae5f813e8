#pragma once
// Axis-aligned displacement manufactured solution (Wallstedt & Guilkey, "An evaluation of explicit
// time integration schemes for the material point method", J. Comput. Phys. 227 (2008) 9628;
// Uintah inputs/MPM/AA.ups; verification CATALOGUE B1). Unit cube of compressible neo-Hookean
// material; every function takes the reference position X and time t.
#include <cmath>
#include <numbers>

#include "core/tensor.hpp"

namespace ballista::mms {

struct AxisAligned {
  double mu = 3846.15;   ///< shear modulus, Pa (CATALOGUE B1)
  double K = 8333.33;    ///< bulk modulus, Pa
  double rho0 = 1.0;     ///< kg/m^3
  double A = 0.05;       ///< amplitude, m

  double lambda() const { return K - 2.0 * mu / 3.0; }
  double youngs() const { return 9.0 * K * mu / (3.0 * K + mu); }
  double c() const { return std::sqrt(youngs() / rho0); }
  /// Phase offsets 0, 2/3, 4/3 (times pi) of the three components.
  static double phase(int i) { return i == 0 ? 0.0 : (i == 1 ? 2.0 / 3.0 : 4.0 / 3.0); }

  double u(const Vec3& X, double t, int i) const {
    using std::numbers::pi;
    return A * std::sin(pi * X[i]) * std::sin(pi * (phase(i) + c() * t));
  }
  Vec3 displacement(const Vec3& X, double t) const { return {{u(X, t, 0), u(X, t, 1), u(X, t, 2)}}; }
  Vec3 velocity(const Vec3& X, double t) const {
    using std::numbers::pi;
    Vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = A * c() * pi * std::sin(pi * X[i]) * std::cos(pi * (phase(i) + c() * t));
    return v;
  }
  /// F_ii = 1 + A pi cos(pi X_i) sin(pi (phase_i + c t)) (CATALOGUE B1).
  Mat3 F(const Vec3& X, double t) const {
    using std::numbers::pi;
    Mat3 f;
    for (int i = 0; i < 3; ++i)
      f(i, i) = 1.0 + A * pi * std::cos(pi * X[i]) * std::sin(pi * (phase(i) + c() * t));
    return f;
  }
  /// Body force per unit mass b_i = pi^2 u_i [mu/rho0 - c^2 - (lambda (ln J - 1) - mu)/(rho0 F_ii^2)]
  /// (CATALOGUE B1; derived from rho0 u'' = Div P + rho0 b with P the neo-Hookean first
  /// Piola-Kirchhoff stress mu (F - F^-T) + lambda ln J F^-T).
  Vec3 body_force(const Vec3& X, double t) const {
    using std::numbers::pi;
    const Mat3 f = F(X, t);
    const double lnJ = std::log(f(0, 0) * f(1, 1) * f(2, 2));
    const double cc = c() * c();
    Vec3 b;
    for (int i = 0; i < 3; ++i)
      b[i] = pi * pi * u(X, t, i) *
             (mu / rho0 - cc - (lambda() * (lnJ - 1.0) - mu) / (rho0 * f(i, i) * f(i, i)));
    return b;
  }
};

}  // namespace ballista::mms
