// The distortion limit of F (materials/distortion.hpp): beyond an RMS isochoric stretch, points of
// models that read only J and R of F have F replaced by J^(1/3) R; hyperelastic models never.
#include <gtest/gtest.h>

#include <cmath>

#include "material_driver.hpp"
#include "materials/distortion.hpp"

namespace test_distortion {

using namespace ballista;
using namespace ballista::test;

namespace {
// Perfectly plastic J2 steel: once yielding, the von Mises stress is the yield stress exactly
// (radial return), whatever F has become.
ParamValues perfect_j2() {
  ParamValues v = elastic_kg(7800, 160e9, 80e9);
  v["yield_stress"] = 300e6;
  v["hardening_modulus"] = 0.0;
  return v;
}
double rms_isochoric_stretch(const Mat3& F) {
  return std::sqrt(ddot(F, F) / (3.0 * std::cbrt(det(F) * det(F))));
}
}  // namespace

// The measure: 1 for any dilatation s I (volume change is not distortion); for the isochoric
// stretch diag(l, 1/sqrt(l), 1/sqrt(l)) it is sqrt((l^2 + 2/l) / 3), and the test flips at it.
TEST(Distortion, MeasureIsTheRmsIsochoricStretch) {
  for (double s : {0.3, 1.0, 4.0}) {
    const Mat3 F = s * Mat3::identity();
    EXPECT_FALSE(beyond_distortion_limit(F, det(F), 1.0 + 1e-9)) << s;
    EXPECT_TRUE(beyond_distortion_limit(F, det(F), 1.0 - 1e-9)) << s;
  }
  for (double l : {2.0, 50.0, 3000.0}) {
    Mat3 F = Mat3::identity();
    F(0, 0) = l;
    F(1, 1) = F(2, 2) = 1.0 / std::sqrt(l);
    const double rms = std::sqrt((l * l + 2.0 / l) / 3.0);
    // Both sides are formed with a few roundings each: 1e-9 relative separates them.
    EXPECT_FALSE(beyond_distortion_limit(F, det(F), rms * (1.0 + 1e-9))) << l;
    EXPECT_TRUE(beyond_distortion_limit(F, det(F), rms * (1.0 - 1e-9))) << l;
  }
}

// A remapped point keeps J, its rotation and its stress: F = J^(1/3) R_n afterwards.
TEST(Distortion, RemapKeepsVolumeRotationAndStress) {
  PointDriver d("j2_plasticity", perfect_j2());
  const Mat3 Q = rotation_about((1.0 / 3.0) * Vec3{{1.0, 2.0, 2.0}}, 0.7);
  Mat3 U = Mat3::identity();
  U(0, 0) = 1.1 * 2000.0;
  U(1, 1) = 1.1 / 2000.0;
  U(2, 2) = 1.1;
  // Start from a rotated, stretched, stressed state (R = Q as the previous steps left it).
  d.F() = Q * U;
  d.R() = Q;
  const Mat3 sigma = rotate_sym(Q, Mat3{{1e8, 2e7, 0, 2e7, -5e7, 0, 0, 0, 3e7}});
  d.stress() = sigma;
  d.set_distortion_limit(1000.0);
  d.set_dt(1e-6);
  d.set_F(0, d.F());
  d.store().view<Mat3>("L")[0] = Mat3{};  // a step without motion
  d.step(1e-6);
  EXPECT_EQ(d.distortion_remaps(), 1);
  const double J = 1.1 * 1.1 * 1.1;
  // J^(1/3) R: the identity of rotation and cube root to a few ulps.
  EXPECT_LT(rel_diff(d.F(), std::cbrt(J) * Q), 1e-14);
  EXPECT_NEAR(det(d.F()), J, 1e-13 * J);
  EXPECT_LT(rel_diff(d.R(), Q), 1e-14);
  // Below the yield surface and without strain the stress is the one it had (to the rounding of
  // the two rotations, unrotated and back).
  EXPECT_LT(rel_diff(d.stress(), sigma), 1e-13);
}

// An isochoric stretching flow L = a diag(1, -1, 0) with a spin, sustained to a stretch e^40 that
// F could not represent: with the limit, F stays within one step's growth of it, det F stays the
// driven J = 1 and the stress stays on the yield surface. Remapped a few times, not every step.
TEST(Distortion, SustainedStretchingFlowStaysBoundedAndPlastic) {
  PointDriver d("j2_plasticity", perfect_j2());
  const double limit = 1000.0, dt = 1e-7, a = 5e5;  // a dt = 0.05 per step
  Mat3 L{};
  L(0, 0) = a;
  L(1, 1) = -a;
  L(0, 1) = 0.3 * a;  // shear: spin and stretch mixed, F not diagonal
  L(1, 0) = -0.1 * a;
  d.set_distortion_limit(limit);
  d.set_dt(dt);
  const int steps = 800;  // a t = 40
  double worst_J = 0.0, worst_vm = 0.0, largest = 0.0;
  for (int s = 0; s < steps; ++s) {
    const Mat3 F_next = (Mat3::identity() + dt * L) * d.F();
    d.set_F(0, F_next);
    d.step(dt);
    // det(I + dt L) = (1 + a dt)(1 - a dt) + 0.03 (a dt)^2: the driven J after s + 1 steps.
    const double Jdriven = std::pow((1 + a * dt) * (1 - a * dt) + 0.03 * a * dt * a * dt, s + 1);
    worst_J = std::max(worst_J, std::abs(det(d.F()) / Jdriven - 1.0));
    largest = std::max(largest, rms_isochoric_stretch(d.F()));
    if (s > 50) worst_vm = std::max(worst_vm, std::abs(von_mises(d.stress()) / 300e6 - 1.0));
  }
  // One step grows the stretch by at most |I + dt L| ~ e^(0.06): the bound with margin.
  EXPECT_LT(largest, 1.1 * limit);
  // det F of a stretch of 1000 sums products of size 1000^2 to J = 1: ~1e6 ulps at each of the
  // few remaps, which keep that J; 1e-8 bounds it with margin (without the limit the stretch
  // e^40 loses J entirely).
  EXPECT_LT(worst_J, 1e-8);
  // Radial return puts the stress on the surface to round-off (1e-9: Newton-free return, a few
  // hundred ulps of a 300 MPa stress accumulated through the rotations).
  EXPECT_LT(worst_vm, 1e-9);
  EXPECT_TRUE(all_finite(d.stress()));
  // The stretch e^40 / 1000 per remap: about 40 / ln(1000 / 1) ~ 6 remaps; each one resets it.
  EXPECT_GE(d.distortion_remaps(), 3);
  EXPECT_LE(d.distortion_remaps(), 20);
}

// A hyperelastic model reads all of F: never remapped, F is what was driven.
TEST(Distortion, HyperelasticModelsAreNeverRemapped) {
  PointDriver d("neo_hookean", elastic_kg(1000, 2e9, 1e6));
  d.set_distortion_limit(2.0);
  d.set_dt(1.0);
  Mat3 F = Mat3::identity();
  F(0, 0) = 10.0;
  F(1, 1) = 0.1;
  d.set_F(0, F);
  d.step(1.0);
  EXPECT_EQ(d.distortion_remaps(), 0);
  EXPECT_EQ(d.F()(0, 0), 10.0);
  EXPECT_EQ(d.F()(1, 1), 0.1);
}

}  // namespace test_distortion
