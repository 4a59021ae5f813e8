// The pinball contact law between OTM bodies (otm/otm_contact.hpp), on configurations whose forces
// follow by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "otm/otm_contact.hpp"

namespace ballista::otm {
namespace {

TEST(PinballContact, RadiusIsHalfTheEdgeOfThePointsCell) {
  // A point of a lattice of spacing s has volume s^3 (3D), s^2 per unit thickness (plane strain) or
  // s^2 r per radian (axisymmetric): its ball's radius is s / 2 in each.
  const double s = 2.0e-3, r = 7.0e-3;
  EXPECT_NEAR(pinball_radius(s * s * s, 0.0, {3, false}), 0.5 * s, 1e-15);
  EXPECT_NEAR(pinball_radius(s * s, 0.0, {2, false}), 0.5 * s, 1e-15);
  EXPECT_NEAR(pinball_radius(s * s * r, r, {2, true}), 0.5 * s, 1e-15);
}

TEST(PinballContact, TwoOverlappingBallsOfDifferentBodiesRepelAlongTheirCentres) {
  // Balls of radius 0.5 mm (V = 1 mm^3) at distance 0.8 mm along (3, 4, 0) / 5: overlap 0.2 mm, force
  // (penalty / 2) min(k_p, k_q) overlap on each, opposite and equal.
  const double V = 1.0e-9, d = 0.8e-3;
  const Vec3 e{{0.6, 0.8, 0.0}};
  const std::vector<Vec3> x{Vec3{{1e-3, 2e-3, 3e-3}}, Vec3{{1e-3, 2e-3, 3e-3}} + d * e};
  const std::vector<double> vol{V, V}, stiff{4.0e6, 1.0e6};
  const std::vector<std::int64_t> body{0, 1};
  std::vector<Vec3> f;
  const Index pairs = pinball_forces(x.data(), vol.data(), body.data(), stiff.data(), 2, 2.0, {3, false}, f);
  EXPECT_EQ(pairs, 1);
  const double expected = 1.0e6 * (1.0e-3 - d);  // penalty 2: k = min = 1e6 N/m
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(f[0][i], -expected * e[i], 1e-9 * expected);
    EXPECT_EQ(f[1][i], -f[0][i]);  // equal and opposite, to the bit: momentum is conserved
  }
}

TEST(PinballContact, NoForceWithinABodyOrBetweenBallsApart) {
  const double V = 1.0e-9;
  const std::vector<Vec3> x{Vec3{{0, 0, 0}}, Vec3{{0.5e-3, 0, 0}}, Vec3{{1.6e-3, 0, 0}}};
  const std::vector<double> vol{V, V, V}, stiff{1.0e6, 1.0e6, 1.0e6};
  // Points 0 and 1 overlap but belong to one body; point 2 is 1.1 mm from point 1 (reach 1 mm).
  const std::vector<std::int64_t> body{0, 0, 1};
  std::vector<Vec3> f;
  EXPECT_EQ(pinball_forces(x.data(), vol.data(), body.data(), stiff.data(), 3, 1.0, {3, false}, f), 0);
  for (const Vec3& fp : f)
    for (int i = 0; i < 3; ++i) EXPECT_EQ(fp[i], 0.0);
}

TEST(PinballContact, ForcesOfATouchingFaceSumToZero) {
  // Two square lattices of spacing s in plane strain, one shifted by a third of a spacing along the
  // face and pushed 0.1 s into the other: each point of the lower face row meets the upper point a
  // third of a spacing along (0.96 s apart; the next is 1.12 s), the pairs push the bodies apart and
  // the forces sum to zero (the pairs' forces cancel exactly, whatever the order).
  const double s = 1.0e-3;
  std::vector<Vec3> x;
  std::vector<std::int64_t> body;
  for (int b = 0; b < 2; ++b)
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 3; ++j) {
        const double y = b == 0 ? -(j + 0.5) * s : (j + 0.5) * s - 0.1 * s;
        x.push_back(Vec3{{(i + (b == 1 ? 1.0 / 3.0 : 0.0)) * s, y, 0.0}});
        body.push_back(b);
      }
  const Index n = static_cast<Index>(x.size());
  const std::vector<double> vol(static_cast<size_t>(n), s * s), stiff(static_cast<size_t>(n), 1.0e7);
  std::vector<Vec3> f;
  const Index pairs = pinball_forces(x.data(), vol.data(), body.data(), stiff.data(), n, 1.0, {2, false}, f);
  EXPECT_EQ(pairs, 12);
  Vec3 sum;
  double largest = 0.0;
  for (const Vec3& fp : f) {
    sum += fp;
    largest = std::max(largest, std::abs(fp[1]));
  }
  EXPECT_GT(largest, 0.0);
  EXPECT_LT(std::abs(sum[0]) + std::abs(sum[1]), 1e-12 * largest);
  // The lower body is pushed down (-y), the upper up, as the overlap says.
  for (Index p = 0; p < n; ++p) {
    if (body[p] == 0) EXPECT_LE(f[p][1], 0.0);
    else EXPECT_GE(f[p][1], 0.0);
  }
}

}  // namespace
}  // namespace ballista::otm
