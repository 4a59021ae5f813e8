#pragma once
// First bending mode of a clamped-free (cantilever) Euler-Bernoulli beam, used as an initial
// velocity field (`initial_state: cantilever_mode1`; thesis seed 000 §6.1.1 after Mast et al.,
// CATALOGUE B4). Mode shape (Blevins, Formulas for Natural Frequency and Mode Shape, 1979,
// Table 8-1, clamped-free; also Rao, Mechanical Vibrations, §8.5):
//   phi(x) = cosh(beta x) - cos(beta x) - s (sinh(beta x) - sin(beta x)),
//   s = (cosh(beta L) + cos(beta L)) / (sinh(beta L) + sin(beta L)),  beta L = 1.87510407,
// x from the clamped root. Euler-Bernoulli kinematics (plane sections stay plane and normal):
// a transverse velocity w_t(x) = V phi(x)/phi(L) comes with the axial velocity -(y - y_c) w_t'(x)
// of the rotating sections, y_c the beam's mid-plane.
#include <cmath>

#include "core/tensor.hpp"

namespace ballista::beam {

/// beta_1 L of the clamped-free beam: the first root of cos(bL) cosh(bL) = -1 (Blevins Table 8-1).
constexpr double kCantileverBetaL1 = 1.8751040687119611;

struct CantileverMode1 {
  double root = 0.0;     ///< x of the clamped end, m
  double length = 1.0;   ///< L, m
  double mid = 0.0;      ///< y of the mid-plane, m
  double tip_speed = 0;  ///< transverse velocity at the tip (x = root + L), m/s

  double beta() const { return kCantileverBetaL1 / length; }
  double s() const {
    const double bl = kCantileverBetaL1;
    return (std::cosh(bl) + std::cos(bl)) / (std::sinh(bl) + std::sin(bl));
  }
  /// phi(x - root) (unnormalised; phi(L) = 2 to 1e-9 for the first mode).
  double phi(double x) const {
    const double bx = beta() * (x - root);
    return std::cosh(bx) - std::cos(bx) - s() * (std::sinh(bx) - std::sin(bx));
  }
  double dphi(double x) const {
    const double bx = beta() * (x - root);
    return beta() * (std::sinh(bx) + std::sin(bx) - s() * (std::cosh(bx) - std::cos(bx)));
  }
  /// Velocity at position X: (-(y - y_c) V phi'/phi(L), V phi/phi(L), 0).
  Vec3 velocity(const Vec3& X) const {
    const double scale = tip_speed / phi(root + length);
    return {{-(X[1] - mid) * scale * dphi(X[0]), scale * phi(X[0]), 0.0}};
  }
};

}  // namespace ballista::beam
