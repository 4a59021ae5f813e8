#pragma once
// kLanes points at a time: 3x3 tensors whose every entry is a vector of kLanes doubles (one lane
// per point), for per-point kernels whose cost is a chain of dependent operations on one point (the
// polar decomposition, a radial return). The lanes fill the target's SIMD width (one register per
// entry: 8 doubles with AVX-512, else 4, AVX2's width) and give the out-of-order core independent
// chains. The width changes no lane's arithmetic (the same operations on each lane), so results
// are the same for either width.
//
// Every function here repeats, operation by operation, the expression of its scalar namesake in
// tensor.hpp: IEEE addition, multiplication, division and square root are exactly rounded lane by
// lane, so a lane's result is the scalar function's up to the compiler's fusing of a multiply
// into an add (FMA), which it decides per context for scalar and vector code alike: the two agree
// to round-off, not bitwise (tests/unit/core/test_lanes.cpp). A solver must therefore take one
// path or the other for a material for the whole run (materials/material_lanes.hpp), never mix
// them by point. Lanes never interact, so a point's result does not depend on which points share
// its group. Change a function here together with its scalar namesake.
#include <cmath>

#include "core/parallel.hpp"  // Index
#include "core/tensor.hpp"

namespace ballista {

#ifdef __AVX512F__
inline constexpr int kLanes = 8;
#else
inline constexpr int kLanes = 4;
#endif
/// kLanes doubles, one per point (GCC/Clang vector extension: + - * / and comparisons lane-wise).
typedef double Lane __attribute__((vector_size(kLanes * sizeof(double))));
/// Result of a lane-wise comparison: all bits set where true, zero where false.
typedef long LaneMask __attribute__((vector_size(kLanes * sizeof(long))));

inline Lane splat(double x) {
  Lane r;
  for (int l = 0; l < kLanes; ++l) r[l] = x;
  return r;
}
/// Lane-wise a where mask, else b.
inline Lane select(LaneMask mask, Lane a, Lane b) { return mask ? a : b; }
inline bool any(LaneMask m) {
  long r = 0;
  for (int l = 0; l < kLanes; ++l) r |= m[l];
  return r != 0;
}
inline Lane lane_sqrt(Lane x) {
  Lane r;
  for (int l = 0; l < kLanes; ++l) r[l] = std::sqrt(x[l]);
  return r;
}

/// Row-major 3x3 tensor of lanes: a[3*i + j] = A_ij of every lane.
struct Mat3L {
  Lane a[9];
  static Mat3L identity() {
    Mat3L m;
    for (int k = 0; k < 9; ++k) m.a[k] = splat(k % 4 == 0 ? 1.0 : 0.0);
    return m;
  }
  /// Lane l's tensor.
  Mat3 lane(int l) const {
    Mat3 m;
    for (int k = 0; k < 9; ++k) m.a[k] = a[k][l];
    return m;
  }
  void set_lane(int l, const Mat3& m) {
    for (int k = 0; k < 9; ++k) a[k][l] = m.a[k];
  }
};

/// The tensors x[idx[l]] of kLanes points, one per lane.
inline Mat3L gather(const Mat3* x, const Index (&idx)[kLanes]) {
  Mat3L m;
  for (int k = 0; k < 9; ++k)
    for (int l = 0; l < kLanes; ++l) m.a[k][l] = x[idx[l]].a[k];
  return m;
}
inline Lane gather(const double* x, const Index (&idx)[kLanes]) {
  Lane r;
  for (int l = 0; l < kLanes; ++l) r[l] = x[idx[l]];
  return r;
}

inline Mat3L operator+(const Mat3L& A, const Mat3L& B) {
  Mat3L C;
  for (int k = 0; k < 9; ++k) C.a[k] = A.a[k] + B.a[k];
  return C;
}
inline Mat3L operator-(const Mat3L& A, const Mat3L& B) {
  Mat3L C;
  for (int k = 0; k < 9; ++k) C.a[k] = A.a[k] - B.a[k];
  return C;
}
inline Mat3L operator*(Lane s, const Mat3L& A) {
  Mat3L C;
  for (int k = 0; k < 9; ++k) C.a[k] = s * A.a[k];
  return C;
}
inline Mat3L operator*(double s, const Mat3L& A) { return splat(s) * A; }
inline Mat3L operator*(const Mat3L& A, const Mat3L& B) {
  Mat3L C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C.a[3 * i + j] = A.a[3 * i] * B.a[j] + A.a[3 * i + 1] * B.a[3 + j] + A.a[3 * i + 2] * B.a[6 + j];
  return C;
}
inline Mat3L transpose(const Mat3L& A) {
  Mat3L T;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T.a[3 * i + j] = A.a[3 * j + i];
  return T;
}
inline Mat3L transpose_times(const Mat3L& A, const Mat3L& B) {
  Mat3L C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C.a[3 * i + j] = A.a[i] * B.a[j] + A.a[3 + i] * B.a[3 + j] + A.a[6 + i] * B.a[6 + j];
  return C;
}
inline Mat3L rotate_sym(const Mat3L& Q, const Mat3L& S) {
  const Mat3L B = Q * S;
  Mat3L C;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const Lane c = B.a[3 * i] * Q.a[3 * j] + B.a[3 * i + 1] * Q.a[3 * j + 1] + B.a[3 * i + 2] * Q.a[3 * j + 2];
      C.a[3 * i + j] = c;
      C.a[3 * j + i] = c;
    }
  return C;
}
inline Mat3L unrotate_sym(const Mat3L& Q, const Mat3L& S) {
  const Mat3L B = S * Q;
  Mat3L C;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const Lane c = Q.a[i] * B.a[j] + Q.a[3 + i] * B.a[3 + j] + Q.a[6 + i] * B.a[6 + j];
      C.a[3 * i + j] = c;
      C.a[3 * j + i] = c;
    }
  return C;
}
inline Lane trace(const Mat3L& A) { return A.a[0] + A.a[4] + A.a[8]; }
inline Lane ddot(const Mat3L& A, const Mat3L& B) {
  Lane s = splat(0.0);
  for (int k = 0; k < 9; ++k) s += A.a[k] * B.a[k];
  return s;
}
inline Mat3L sym(const Mat3L& A) { return 0.5 * (A + transpose(A)); }
inline Mat3L deviator(const Mat3L& A) {
  Mat3L D = A;
  const Lane m = trace(A) / 3.0;
  D.a[0] -= m;
  D.a[4] -= m;
  D.a[8] -= m;
  return D;
}
inline Lane det(const Mat3L& A) {
  return A.a[0] * (A.a[4] * A.a[8] - A.a[5] * A.a[7]) - A.a[1] * (A.a[3] * A.a[8] - A.a[5] * A.a[6]) +
         A.a[2] * (A.a[3] * A.a[7] - A.a[4] * A.a[6]);
}
inline Mat3L cofactor(const Mat3L& A) {
  Mat3L C;
  C.a[0] = A.a[4] * A.a[8] - A.a[5] * A.a[7];
  C.a[1] = A.a[5] * A.a[6] - A.a[3] * A.a[8];
  C.a[2] = A.a[3] * A.a[7] - A.a[4] * A.a[6];
  C.a[3] = A.a[2] * A.a[7] - A.a[1] * A.a[8];
  C.a[4] = A.a[0] * A.a[8] - A.a[2] * A.a[6];
  C.a[5] = A.a[1] * A.a[6] - A.a[0] * A.a[7];
  C.a[6] = A.a[1] * A.a[5] - A.a[2] * A.a[4];
  C.a[7] = A.a[2] * A.a[3] - A.a[0] * A.a[5];
  C.a[8] = A.a[0] * A.a[4] - A.a[1] * A.a[3];
  return C;
}
inline Mat3L inverse(const Mat3L& A) { return (1.0 / det(A)) * transpose(cofactor(A)); }

}  // namespace ballista
