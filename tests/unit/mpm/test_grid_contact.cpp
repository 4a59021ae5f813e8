// apply_grid_contact (src/mpm/grid_contact.hpp) on single nodes against the closed forms of the
// Bardenhagen et al. (2000, 2001) correction: two fields meeting along a known normal; and nodes
// where three or more fields meet against conservation (momentum exact, kinetic energy lost).
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mpm/grid_contact.hpp"

namespace test_grid_contact {

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

TEST(GridContact, FieldsThatFillLittleOfTheNodeAreNotInContact) {
  // The gap check (contact.min_volume_fraction): two fields approaching at one node of a 2D grid
  // with h = 0.5 (node volume h^2 = 0.25 per unit thickness) are corrected only when their
  // particles fill at least the given fraction of it. 0.1 of the node (a gap of most of a cell
  // between the bodies): left alone at 0.5; 0.6 of it (bodies touching): corrected as without
  // the check.
  GridGeometry geom;
  geom.dim = 2;
  geom.h = 0.5;
  geom.nodes[0] = geom.nodes[1] = 3;
  const Index node = geom.node_index(1, 1, 0);
  const Index nn = geom.node_count();
  const std::vector<Vec3> g0 = {Vec3{{3.0, 0.0, 0.0}}, Vec3{{-1.0, 0.0, 0.0}}};
  for (const double filled : {0.1, 0.6}) {
    std::vector<double> mass(2 * nn, 0.0), volume(2 * nn, 0.0);
    std::vector<Vec3> grad(2 * nn), vel(2 * nn);
    mass[node] = 2.0;
    mass[nn + node] = 3.0;
    grad[node] = g0[0];
    grad[nn + node] = g0[1];
    volume[node] = volume[nn + node] = 0.5 * filled * 0.25;
    vel[node] = Vec3{{5.0, 0.0, 0.0}};
    vel[nn + node] = Vec3{{-2.0, 0.0, 0.0}};
    const std::vector<double> friction(4, 0.0);
    FieldGrid g{2, nn, mass.data(), grad.data(), friction.data()};
    g.volume = volume.data();
    g.min_volume_fraction = 0.5;
    g.geom = &geom;
    apply_grid_contact(g, vel.data(), kTiny);
    if (filled < 0.5) {
      EXPECT_EQ(vel[node][0], 5.0);
      EXPECT_EQ(vel[nn + node][0], -2.0);
    } else {
      const double vcm = (2.0 * 5.0 + 3.0 * -2.0) / 5.0;
      EXPECT_NEAR(vel[node][0], vcm, 1e-14);
      EXPECT_NEAR(vel[nn + node][0], vcm, 1e-14);
    }
  }
}

namespace {

struct Node {
  std::vector<double> mass;
  std::vector<Vec3> grad, v0, vel;
  std::vector<double> friction;
  ContactWork work;
  std::vector<Vec3> impulse, friction_impulse;
};

Node correct_node(std::vector<double> mass, std::vector<Vec3> grad, std::vector<Vec3> v0, double mu) {
  Node n{std::move(mass), std::move(grad), v0, v0, {}, {}, {}, {}};
  const int nf = static_cast<int>(n.mass.size());
  n.friction.assign(static_cast<size_t>(nf) * nf, mu);
  n.impulse.assign(n.mass.size(), Vec3{});
  n.friction_impulse.assign(n.mass.size(), Vec3{});
  const FieldGrid g{nf, 1, n.mass.data(), n.grad.data(), n.friction.data()};
  n.work = apply_grid_contact(g, n.vel.data(), kTiny, n.impulse.data(), n.friction_impulse.data());
  return n;
}

}  // namespace

TEST(GridContact, ThreeFieldsAtANodeCollidePairByPairAndKeepItsMomentum) {
  // Unit masses, outward vectors (1,0,0), (-1,0,0), (0,1,0), velocities (1,0,0), (-1,0,0), 0. Each
  // field's own normal against the centre of mass would correct the first two by -(2/5)(2,-1,0)
  // and -(2/5)(-2,-1,0): (0, 0.8, 0) kg m/s made at the node. Pair by pair, 0 and 1 meet head on
  // along x (reduced mass 1/2, relative normal velocity 2) and stop; the pairs with field 2 then
  // have no relative velocity. Exact: all three at rest, momentum 0, kinetic energy 1 J lost.
  const Node n = correct_node({1.0, 1.0, 1.0}, {Vec3{{1.0, 0.0, 0.0}}, Vec3{{-1.0, 0.0, 0.0}}, Vec3{{0.0, 1.0, 0.0}}},
                              {Vec3{{1.0, 0.0, 0.0}}, Vec3{{-1.0, 0.0, 0.0}}, Vec3{}}, 0.0);
  for (int f = 0; f < 3; ++f)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(n.vel[f][a], 0.0) << "field " << f << " component " << a;
  EXPECT_DOUBLE_EQ(n.work.total, -1.0);
  EXPECT_EQ(n.work.friction, 0.0);
  // The impulses handed back are the velocity changes.
  EXPECT_EQ(n.impulse[0][0], -1.0);
  EXPECT_EQ(n.impulse[1][0], 1.0);
}

TEST(GridContact, ManyFieldsWithFrictionKeepMomentumAndLoseEnergy) {
  // Four fields of unequal mass in general position, with friction: whatever the pairs do, each
  // impulse is equal and opposite (momentum to round-off, 1e-13 of the momenta involved), each
  // removes kinetic energy (the work is negative and equals the kinetic-energy change), the
  // friction work is a loss no larger than the whole, and after the sweeps no pair approaches
  // along its normal by more than a small fraction of what it did (the sweeps settle).
  const std::vector<double> mass = {1.0, 2.5, 0.7, 4.0};
  const std::vector<Vec3> grad = {Vec3{{1.0, 0.2, 0.0}}, Vec3{{-0.8, 0.1, 0.3}}, Vec3{{0.1, 1.0, -0.2}},
                                  Vec3{{0.0, -0.9, 0.4}}};
  const std::vector<Vec3> v0 = {Vec3{{30.0, -5.0, 2.0}}, Vec3{{-20.0, 8.0, 1.0}}, Vec3{{3.0, -40.0, 0.0}},
                                Vec3{{-1.0, 25.0, -6.0}}};
  const Node n = correct_node(mass, grad, v0, 0.3);
  Vec3 p0, p1;
  double ke0 = 0.0, ke1 = 0.0;
  for (size_t f = 0; f < mass.size(); ++f) {
    p0 += mass[f] * v0[f];
    p1 += mass[f] * n.vel[f];
    ke0 += ke(mass[f], v0[f]);
    ke1 += ke(mass[f], n.vel[f]);
  }
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(p1[a], p0[a], 1e-13 * 200.0);
  EXPECT_LT(ke1, ke0);
  EXPECT_NEAR(n.work.total, ke1 - ke0, 1e-12 * ke0);
  EXPECT_LT(n.work.friction, 0.0);
  EXPECT_GE(n.work.friction, n.work.total);
  double worst0 = 0.0, worst1 = 0.0;
  for (size_t a = 0; a < mass.size(); ++a)
    for (size_t b = a + 1; b < mass.size(); ++b) {
      Vec3 nab = grad[a] - grad[b];
      nab = (1.0 / norm(nab)) * nab;
      worst0 = std::max(worst0, dot(v0[a] - v0[b], nab));
      worst1 = std::max(worst1, dot(n.vel[a] - n.vel[b], nab));
    }
  EXPECT_GT(worst0, 10.0);
  EXPECT_LT(worst1, 1e-2 * worst0);
}

TEST(GridContact, TwoFieldsAmongThreeMeetAsTwoFieldsDo) {
  // A third field too light to count (below tiny_mass) leaves a node of two fields: the
  // correction is the two-field one, bit for bit.
  const Pair two = correct(2.0, 3.0, Vec3{{5.0, 1.0, 0.0}}, Vec3{{-2.0, -4.0, 0.5}}, 0.2);
  const Node three = correct_node({2.0, 3.0, 1e-300}, {Vec3{{3.0, 0.0, 0.0}}, Vec3{{-1.0, 0.0, 0.0}}, Vec3{{0.0, 1.0, 0.0}}},
                                  {Vec3{{5.0, 1.0, 0.0}}, Vec3{{-2.0, -4.0, 0.5}}, Vec3{{9.0, 9.0, 9.0}}}, 0.2);
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(three.vel[0][a], two.v1[a]);
    EXPECT_EQ(three.vel[1][a], two.v2[a]);
  }
  EXPECT_EQ(three.vel[2][0], 9.0);
}

TEST(GridContact, NodeVolumesTileTheGrid) {
  // The node volumes the gap check compares with sum to the volume of the box the nodes span
  // (half cells at the faces): h^2 per interior node in plane strain; in axisymmetric the
  // integral of r dr, sum = R^2 / 2 per radian and unit height over the nodes of one row, and
  // r_I h for a node off the axis.
  GridGeometry g;
  g.dim = 2;
  g.h = 0.25;
  g.nodes[0] = 5;
  g.nodes[1] = 4;
  EXPECT_DOUBLE_EQ(g.node_volume(g.node_index(2, 1, 0), false), 0.0625);
  const double R = 4 * g.h;
  double row = 0.0;
  for (int i = 0; i < g.nodes[0]; ++i) {
    // A face node's outer half cell lies outside the box: take the inner half only.
    const double v = g.node_volume(g.node_index(i, 1, 0), true) / g.h;
    const double outer = i == g.nodes[0] - 1 ? 0.5 * ((R + 0.5 * g.h) * (R + 0.5 * g.h) - R * R) : 0.0;
    row += v - outer;
  }
  EXPECT_NEAR(row, 0.5 * R * R, 1e-15);
  EXPECT_DOUBLE_EQ(g.node_volume(g.node_index(2, 1, 0), true), 2 * g.h * g.h * g.h);
}

}  // namespace test_grid_contact
