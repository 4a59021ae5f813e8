#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/lanes.hpp"
#include "core/polar_lanes.hpp"
#include "materials/strain_increment.hpp"

namespace test_lanes {

using namespace ballista;

// Each lane function evaluates its scalar namesake's expression (lanes.hpp). The compiler may fuse
// a multiply into an add (FMA) in one and not in the other, which moves a result by round-off
// only: each such operation by at most an ulp of its terms. The bounds below (1e-14 of the
// operands' scale, about 50 ulps) leave room for chains of a few dozen operations and catch any
// wrong index or sign, which errs by O(1).
namespace {
double scale(const Mat3& m) {
  double x = 0.0;
  for (double v : m.a) x = std::max(x, std::abs(v));
  return x;
}
/// a and b agree to 1e-14 of `of` (the size of the terms that were summed).
bool agree(const Mat3& a, const Mat3& b, double of) { return scale(a - b) <= 1e-14 * of; }
bool agree(const Mat3& a, const Mat3& b) { return agree(a, b, scale(b)); }
bool agree(double a, double b, double of) { return std::abs(a - b) <= 1e-14 * of; }

Mat3 random_matrix(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Mat3 m;
  for (double& x : m.a) x = scale * u(rng);
  return m;
}
Mat3 random_rotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 axis{{u(rng), u(rng), u(rng)}};
  axis = (1.0 / norm(axis)) * axis;
  return rotation_about(axis, max_angle * u(rng));
}
}  // namespace

TEST(Lanes, TensorAlgebraIsTheScalarsLaneByLane) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    Mat3 A[kLanes], B[kLanes];
    Mat3L AL, BL;
    for (int l = 0; l < kLanes; ++l) {
      A[l] = Mat3::identity() + random_matrix(rng, 0.3);  // well conditioned: the inverse keeps the bound
      B[l] = random_matrix(rng, 2.0);
      B[l] = sym(B[l]);
      AL.set_lane(l, A[l]);
      BL.set_lane(l, B[l]);
    }
    const Mat3L prod = AL * BL, tt = transpose_times(AL, BL), rot = rotate_sym(AL, BL), unrot = unrotate_sym(AL, BL);
    const Mat3L inv = inverse(AL), mid = midpoint_strain_increment(0.1 * BL), s = sym(AL), dev = deviator(AL);
    const Lane d = det(AL), dd = ddot(AL, BL), tr = trace(AL);
    for (int l = 0; l < kLanes; ++l) {
      const double ab = 3.0 * scale(A[l]) * scale(B[l]), a = scale(A[l]);
      EXPECT_TRUE(agree(prod.lane(l), A[l] * B[l], ab));
      EXPECT_TRUE(agree(tt.lane(l), transpose_times(A[l], B[l]), ab));
      EXPECT_TRUE(agree(rot.lane(l), rotate_sym(A[l], B[l]), 3.0 * a * ab));
      EXPECT_TRUE(agree(unrot.lane(l), unrotate_sym(A[l], B[l]), 3.0 * a * ab));
      EXPECT_TRUE(agree(inv.lane(l), inverse(A[l])));
      EXPECT_TRUE(agree(mid.lane(l), midpoint_strain_increment(0.1 * B[l])));
      EXPECT_TRUE(agree(s.lane(l), sym(A[l])));
      EXPECT_TRUE(agree(dev.lane(l), deviator(A[l]), a));
      EXPECT_TRUE(agree(d[l], det(A[l]), 6.0 * a * a * a));
      EXPECT_TRUE(agree(dd[l], ddot(A[l], B[l]), 3.0 * ab));
      EXPECT_TRUE(agree(tr[l], trace(A[l]), 3.0 * a));
    }
  }
}

// The lanes of one call take different paths through polar_rotation: a warm start one step old
// (two Newton iterations), a rotation far from the guess (more iterations), a guess 3 rad away
// (many iterations or Higham's fallback), a non-finite F, and a guess 1e-9 rad away. Each lane
// must be what the scalar function returns for it (a non-finite lane: non-finite).
TEST(Lanes, PolarRotationIsTheScalarsLaneByLane) {
  std::mt19937 rng(11);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int trial = 0; trial < 400; ++trial) {
    Mat3L F, guess;
    Mat3 Fs[kLanes], Gs[kLanes];
    for (int l = 0; l < kLanes; ++l) {
      const Mat3 R = random_rotation(rng, 3.1);
      const Mat3 U = Mat3::identity() + sym(random_matrix(rng, 0.3));
      Fs[l] = R * U;
      const int kind = (trial + l) % 5;
      if (kind == 0) Gs[l] = R * random_rotation(rng, 1e-3);
      else if (kind == 1) Gs[l] = R * random_rotation(rng, 0.8);
      else if (kind == 2) Gs[l] = R * rotation_about(Vec3{{0, 0, 1}}, 3.0);
      else if (kind == 3) { Gs[l] = R; Fs[l].a[4] = nan; }
      else Gs[l] = R * random_rotation(rng, 1e-9);
      F.set_lane(l, Fs[l]);
      guess.set_lane(l, Gs[l]);
    }
    const Mat3L R = polar_rotation(F, guess);
    for (int l = 0; l < kLanes; ++l) {
      const Mat3 want = polar_rotation(Fs[l], Gs[l]);
      const Mat3 got = R.lane(l);
      if (all_finite(want))
        EXPECT_TRUE(agree(got, want)) << "trial " << trial << " lane " << l;
      else
        EXPECT_FALSE(all_finite(got)) << "trial " << trial << " lane " << l;
    }
  }
}

}  // namespace test_lanes
