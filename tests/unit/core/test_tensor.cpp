#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "core/polar.hpp"
#include "core/tensor.hpp"

namespace test_tensor {

using namespace ballista;

namespace {
Mat3 random_matrix(std::mt19937& rng, double amp = 1.0) {
  std::uniform_real_distribution<double> u(-amp, amp);
  Mat3 A;
  for (double& a : A.a) a = u(rng);
  return A;
}
Vec3 random_unit(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Vec3 x{{u(rng), u(rng), u(rng)}};
  return (1.0 / norm(x)) * x;
}
// Reference products by the index definition.
Mat3 mul_ref(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) C(i, j) += A(i, k) * B(k, j);
  return C;
}
}  // namespace

// Identities are checked to 1e-13 relative: each side is a handful of flops on O(1) entries, and
// the inverse of a random matrix is kept well conditioned by rejecting |det| < 0.05.
TEST(Tensor, ProductsAndTransposes) {
  std::mt19937 rng(1);
  for (int k = 0; k < 100; ++k) {
    const Mat3 A = random_matrix(rng), B = random_matrix(rng);
    EXPECT_LT(frobenius(A * B - mul_ref(A, B)), 1e-14);
    EXPECT_LT(frobenius(transpose_times(A, B) - mul_ref(transpose(A), B)), 1e-14);
    EXPECT_LT(frobenius(times_transpose(A, B) - mul_ref(A, transpose(B))), 1e-14);
    EXPECT_EQ(frobenius(transpose(transpose(A)) - A), 0.0);
    const Vec3 x{{0.3, -1.2, 0.7}};
    const Vec3 y = A * x;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(y[i], A(i, 0) * x[0] + A(i, 1) * x[1] + A(i, 2) * x[2], 1e-15);
    EXPECT_LT(frobenius(sym(A) + skew(A) - A), 1e-15);
    EXPECT_LT(frobenius(sym(A) - transpose(sym(A))), 1e-15);
    EXPECT_NEAR(trace(deviator(A)), 0.0, 1e-15);
    EXPECT_NEAR(ddot(A, B), trace(transpose_times(A, B)), 1e-14);
  }
}

TEST(Tensor, DeterminantInverseCofactor) {
  std::mt19937 rng(2);
  int tested = 0;
  while (tested < 200) {
    const Mat3 A = random_matrix(rng), B = random_matrix(rng);
    if (std::abs(det(A)) < 0.05) continue;
    ++tested;
    EXPECT_NEAR(det(A * B), det(A) * det(B), 1e-13);
    EXPECT_NEAR(det(transpose(A)), det(A), 1e-14);
    EXPECT_NEAR(det(2.0 * A), 8.0 * det(A), 1e-13);
    const Mat3 Ai = inverse(A);
    const double cond = frobenius(A) * frobenius(Ai);
    EXPECT_LT(frobenius(A * Ai - Mat3::identity()), 1e-15 * cond * 10);
    EXPECT_LT(frobenius(Ai * A - Mat3::identity()), 1e-15 * cond * 10);
    // cof(A) = det(A) A^{-T};  A cof(A)^T = det(A) I;  inverse_transpose = transpose(inverse).
    EXPECT_LT(frobenius(cofactor(A) - det(A) * transpose(Ai)), 1e-15 * cond * 10);
    EXPECT_LT(frobenius(times_transpose(A, cofactor(A)) - det(A) * Mat3::identity()), 1e-14);
    EXPECT_LT(frobenius(inverse_transpose(A) - transpose(Ai)), 1e-15 * cond * 10);
    // d det / dA = cof(A): central difference, h = 1e-6, O(h^2) truncation -> 1e-9.
    const double h = 1e-6;
    for (int i = 0; i < 9; ++i) {
      Mat3 Ap = A, Am = A;
      Ap.a[i] += h;
      Am.a[i] -= h;
      EXPECT_NEAR((det(Ap) - det(Am)) / (2 * h), cofactor(A).a[i], 1e-9);
    }
  }
  // The cofactor stays defined for a singular matrix (rank 2): A cof(A)^T = 0.
  const Mat3 S{{1, 2, 3, 4, 5, 6, 7, 8, 9}};
  EXPECT_EQ(det(S), 0.0);
  EXPECT_LT(frobenius(times_transpose(S, cofactor(S))), 1e-13);
  EXPECT_GT(frobenius(cofactor(S)), 1.0);
  EXPECT_EQ(det(Mat3::identity()), 1.0);
  EXPECT_EQ(det(Mat3::diag(2, 3, 4)), 24.0);
}

// rotation_about: orthogonal, det +1, leaves the axis fixed, turns a perpendicular vector by the
// angle; composition about one axis adds angles; rotate/unrotate are inverse.
TEST(Tensor, RotationAbout) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-7.0, 7.0);
  for (int k = 0; k < 100; ++k) {
    const Vec3 n = random_unit(rng);
    const double a = u(rng), b = u(rng);
    const Mat3 R = rotation_about(n, a);
    EXPECT_LT(frobenius(transpose_times(R, R) - Mat3::identity()), 1e-15 * 10);
    EXPECT_NEAR(det(R), 1.0, 1e-14);
    const Vec3 Rn = R * n;
    EXPECT_LT(norm(Rn - n), 1e-15 * 10);
    Vec3 p = cross(n, random_unit(rng));
    p = (1.0 / norm(p)) * p;
    EXPECT_NEAR(dot(R * p, p), std::cos(a), 1e-14);
    EXPECT_NEAR(dot(cross(p, R * p), n), std::sin(a), 1e-14);
    EXPECT_LT(frobenius(rotation_about(n, a) * rotation_about(n, b) - rotation_about(n, a + b)), 1e-14);
    const Mat3 S = sym(random_matrix(rng));
    EXPECT_LT(frobenius(unrotate(R, rotate(R, S)) - S), 1e-14);
    EXPECT_LT(frobenius(rotate(R, S) - mul_ref(mul_ref(R, S), transpose(R))), 1e-14);
    EXPECT_NEAR(trace(rotate(R, S)), trace(S), 1e-14);
    EXPECT_NEAR(von_mises(rotate(R, S)), von_mises(S), 1e-13);
  }
  // 90 deg about z maps x to y.
  const Mat3 Rz = rotation_about(Vec3{{0, 0, 1}}, std::acos(0.0));
  const Vec3 y = Rz * Vec3{{1, 0, 0}};
  EXPECT_NEAR(y[0], 0.0, 1e-16);
  EXPECT_NEAR(y[1], 1.0, 1e-16);
}

// von Mises stress: uniaxial sigma -> |sigma|; pure shear tau -> sqrt(3)|tau|; pressure -> 0.
TEST(Tensor, VonMises) {
  EXPECT_NEAR(von_mises(Mat3::diag(-250.0, 0, 0)), 250.0, 1e-12);
  Mat3 shear;
  shear(0, 1) = shear(1, 0) = 100.0;
  EXPECT_NEAR(von_mises(shear), std::sqrt(3.0) * 100.0, 1e-12);
  EXPECT_NEAR(von_mises(Mat3::diag(-7, -7, -7)), 0.0, 1e-12);
}

// Warm-started polar decomposition over many steps (as the material adapter uses it: each step's
// guess is the previous R) must not drift from orthogonality. F(t) = Q(2 pi t) diag(1 - 0.002 t,
// 1, 1), 2e5 steps: R stays orthogonal to round-off (4e-15) and equal to a cold start.
TEST(Tensor, PolarWarmStartDoesNotDrift) {
  const int N = 200000;
  Mat3 R = Mat3::identity();
  double worst = 0.0;
  for (int n = 1; n <= N; ++n) {
    const double t = double(n) / N;
    const Mat3 F = rotation_about(Vec3{{0, 0, 1}}, 2.0 * std::numbers::pi * t) * Mat3::diag(1.0 - 0.002 * t, 1.0, 1.0);
    R = polar_rotation(F, R);
    if (n % 1000 == 0) worst = std::max(worst, frobenius(transpose_times(R, R) - Mat3::identity()));
  }
  // Re-orthogonalisation triggers when any entry of R^T R - I exceeds 4e-15, so the Frobenius
  // norm stays below 3 x 4e-15 = 1.2e-14; without it: 1.6e-11 (round-off accumulates).
  EXPECT_LT(worst, 1.2e-14);
  const Mat3 F1 = rotation_about(Vec3{{0, 0, 1}}, 2.0 * std::numbers::pi) * Mat3::diag(0.998, 1.0, 1.0);
  EXPECT_LT(frobenius(R - polar_rotation(F1)), 4e-15);
}

// Polar decomposition of random F (general stretch, not only SPD-perturbed): R orthogonal with
// det +1, U symmetric positive definite, F = R U, to 1e-13 relative.
TEST(Tensor, PolarRandomF) {
  std::mt19937 rng(4);
  int tested = 0;
  while (tested < 200) {
    const Mat3 F = Mat3::identity() + random_matrix(rng, 0.7);
    if (det(F) < 0.05) continue;
    ++tested;
    Mat3 R, U;
    polar_decompose(F, R, U);
    EXPECT_LT(frobenius(transpose_times(R, R) - Mat3::identity()), 1e-14);
    EXPECT_NEAR(det(R), 1.0, 1e-14);
    EXPECT_LT(frobenius(R * U - F) / frobenius(F), 1e-13);
    EXPECT_LT(frobenius(U - transpose(U)), 1e-15);
    // U positive definite: leading principal minors > 0.
    EXPECT_GT(U(0, 0), 0.0);
    EXPECT_GT(U(0, 0) * U(1, 1) - U(0, 1) * U(1, 0), 0.0);
    EXPECT_GT(det(U), 0.0);
  }
}

}  // namespace test_tensor
