// apply_grid_contact (src/mpm/grid_contact.hpp) on single nodes against the closed forms of the
// Bardenhagen et al. (2000, 2001) correction: two fields meeting along a known normal.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mpm/grid_contact.hpp"

using namespace ballista;

namespace {

constexpr double kTiny = 1e-200;

/// One node, two fields with masses m1, m2, outward vectors g1 = +x (field 0 lies at -x) and
/// g2 = -x, velocities v1, v2; friction mu. Returns the corrected velocities and the work.
struct Pair {
  Vec3 v1, v2;
  ContactWork work;
};
Pair correct(double m1, double m2, Vec3 v1, Vec3 v2, double mu) {
  const std::vector<double> mass = {m1, m2};
  const std::vector<Vec3> grad = {Vec3{{3.0, 0.0, 0.0}}, Vec3{{-1.0, 0.0, 0.0}}};  // unequal lengths
  const std::vector<double> friction = {mu, mu, mu, mu};
  std::vector<Vec3> vel = {v1, v2};
  const FieldGrid g{2, 1, mass.data(), grad.data(), friction.data()};
  Pair p;
  p.work = apply_grid_contact(g, vel.data(), kTiny);
  p.v1 = vel[0];
  p.v2 = vel[1];
  return p;
}

double ke(double m, const Vec3& v) { return 0.5 * m * dot(v, v); }

}  // namespace

TEST(GridContact, ApproachingFieldsLoseTheirNormalRelativeVelocityAndKeepMomentum) {
  // Frictionless head-on: both end at the centre-of-mass normal velocity, tangential velocities
  // untouched (mu = 0); momentum exact; the work is the kinetic-energy change.
  const double m1 = 2.0, m2 = 3.0;
  const Vec3 v1{{5.0, 1.0, 0.0}}, v2{{-2.0, -4.0, 0.5}};
  const Pair p = correct(m1, m2, v1, v2, 0.0);
  const double vcm_x = (m1 * 5.0 + m2 * -2.0) / (m1 + m2);
  EXPECT_NEAR(p.v1[0], vcm_x, 1e-14);
  EXPECT_NEAR(p.v2[0], vcm_x, 1e-14);
  EXPECT_EQ(p.v1[1], 1.0);
  EXPECT_EQ(p.v2[1], -4.0);
  EXPECT_EQ(p.v2[2], 0.5);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(m1 * p.v1[a] + m2 * p.v2[a], m1 * v1[a] + m2 * v2[a], 1e-13);
  const double dke = ke(m1, p.v1) + ke(m2, p.v2) - ke(m1, v1) - ke(m2, v2);
  EXPECT_NEAR(p.work.total, dke, 1e-12);
  EXPECT_LT(p.work.total, 0.0);
  EXPECT_EQ(p.work.friction, 0.0);
}

TEST(GridContact, SeparatingFieldsAreLeftAlone) {
  const Vec3 v1{{-1.0, 2.0, 0.0}}, v2{{1.0, 0.0, 0.0}};
  const Pair p = correct(1.0, 1.0, v1, v2, 0.5);
  EXPECT_EQ(p.v1[0], v1[0]);
  EXPECT_EQ(p.v1[1], v1[1]);
  EXPECT_EQ(p.v2[0], v2[0]);
  EXPECT_EQ(p.work.total, 0.0);
}

TEST(GridContact, CoulombFrictionSlipsOrSticks) {
  // Equal masses, normal approach 2 (each field 1 relative to the centre of mass), sliding 10
  // (5 each). Slip: the tangential change is mu times the normal one (mu * 1 per field). Stick
  // (mu >= 5): the tangential relative velocity is removed entirely.
  const Vec3 v1{{1.0, 5.0, 0.0}}, v2{{-1.0, -5.0, 0.0}};
  const Pair slip = correct(1.0, 1.0, v1, v2, 0.3);
  EXPECT_NEAR(slip.v1[0], 0.0, 1e-14);
  EXPECT_NEAR(slip.v1[1], 5.0 - 0.3, 1e-14);
  EXPECT_NEAR(slip.v2[1], -5.0 + 0.3, 1e-14);
  // Frictional work: m mu' dvn (mu' dvn / 2 - vt) per field = 0.3 (0.15 - 5) each.
  EXPECT_NEAR(slip.work.friction, 2 * 0.3 * (0.15 - 5.0), 1e-12);
  const Pair stick = correct(1.0, 1.0, v1, v2, 10.0);
  EXPECT_NEAR(stick.v1[1], 0.0, 1e-14);
  EXPECT_NEAR(stick.v2[1], 0.0, 1e-14);
  EXPECT_NEAR(stick.work.total, -(ke(1.0, v1) + ke(1.0, v2)), 1e-12);  // both stop: all KE gone
}

TEST(GridContact, ANodeOfOneFieldIsUntouched) {
  const std::vector<double> mass = {1.0, 0.0};
  const std::vector<Vec3> grad = {Vec3{{1.0, 0.0, 0.0}}, Vec3{}};
  const std::vector<double> friction(4, 0.5);
  std::vector<Vec3> vel = {Vec3{{3.0, 0.0, 0.0}}, Vec3{}};
  const FieldGrid g{2, 1, mass.data(), grad.data(), friction.data()};
  const ContactWork w = apply_grid_contact(g, vel.data(), kTiny);
  EXPECT_EQ(vel[0][0], 3.0);
  EXPECT_EQ(w.total, 0.0);
}
