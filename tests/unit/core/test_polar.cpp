#include <gtest/gtest.h>

#include <random>

#include "core/polar.hpp"

namespace test_polar {

using namespace ballista;

// F = R U with a known rotation and a symmetric positive-definite stretch must return that R
// to round-off (1e-12 relative: the Newton iteration converges quadratically to machine precision).
TEST(Polar, RecoversKnownRotation) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    Vec3 axis{{u(rng), u(rng), u(rng)}};
    axis = (1.0 / norm(axis)) * axis;
    const Mat3 R = rotation_about(axis, 3.0 * u(rng));
    Mat3 A;
    for (double& a : A.a) a = 0.3 * u(rng);
    const Mat3 U = Mat3::identity() + sym(A) + 0.5 * Mat3::identity();  // SPD for |A| small
    const Mat3 F = R * U;
    Mat3 Rc, Uc;
    polar_decompose(F, Rc, Uc);
    EXPECT_LT(frobenius(Rc - R), 1e-12);
    EXPECT_LT(frobenius(Uc - U), 1e-12);
    // Warm start from a nearby rotation gives the same answer.
    const Mat3 guess = rotation_about(axis, 0.0) * R;
    EXPECT_LT(frobenius(polar_rotation(F, guess) - R), 1e-12);
  }
}

}  // namespace test_polar
