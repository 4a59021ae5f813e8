#pragma once
// Small fixed-size vectors and 3x3 tensors for per-point kernels.
// Plain aggregates of doubles (standard layout) so that SoA field storage can hand out
// typed views without copies; every operation is inline and allocation-free.
#include <cmath>

namespace ballista {

struct Vec3 {
  double v[3]{0.0, 0.0, 0.0};
  double& operator[](int i) { return v[i]; }
  double operator[](int i) const { return v[i]; }
};

/// Row-major 3x3 tensor: a[3*i + j] = A_ij.
struct Mat3 {
  double a[9]{0, 0, 0, 0, 0, 0, 0, 0, 0};
  double& operator()(int i, int j) { return a[3 * i + j]; }
  double operator()(int i, int j) const { return a[3 * i + j]; }
  static Mat3 identity() { return diag(1.0, 1.0, 1.0); }
  static Mat3 diag(double d0, double d1, double d2) {
    Mat3 m;
    m.a[0] = d0;
    m.a[4] = d1;
    m.a[8] = d2;
    return m;
  }
};

inline Vec3 operator+(const Vec3& x, const Vec3& y) { return {{x[0] + y[0], x[1] + y[1], x[2] + y[2]}}; }
inline Vec3 operator-(const Vec3& x, const Vec3& y) { return {{x[0] - y[0], x[1] - y[1], x[2] - y[2]}}; }
inline Vec3 operator*(double s, const Vec3& x) { return {{s * x[0], s * x[1], s * x[2]}}; }
inline Vec3& operator+=(Vec3& x, const Vec3& y) { x[0] += y[0]; x[1] += y[1]; x[2] += y[2]; return x; }
inline double dot(const Vec3& x, const Vec3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; }
inline double norm(const Vec3& x) { return std::sqrt(dot(x, x)); }
inline Vec3 cross(const Vec3& x, const Vec3& y) {
  return {{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]}};
}

inline Mat3 operator+(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int k = 0; k < 9; ++k) C.a[k] = A.a[k] + B.a[k];
  return C;
}
inline Mat3 operator-(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int k = 0; k < 9; ++k) C.a[k] = A.a[k] - B.a[k];
  return C;
}
inline Mat3 operator*(double s, const Mat3& A) { Mat3 C; for (int k = 0; k < 9; ++k) C.a[k] = s * A.a[k]; return C; }
inline Mat3& operator+=(Mat3& A, const Mat3& B) { for (int k = 0; k < 9; ++k) A.a[k] += B.a[k]; return A; }
inline Mat3& operator*=(Mat3& A, double s) { for (int k = 0; k < 9; ++k) A.a[k] *= s; return A; }

inline Mat3 operator*(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C.a[3 * i + j] = A.a[3 * i] * B.a[j] + A.a[3 * i + 1] * B.a[3 + j] + A.a[3 * i + 2] * B.a[6 + j];
  return C;
}
inline Vec3 operator*(const Mat3& A, const Vec3& x) {
  return {{A.a[0] * x[0] + A.a[1] * x[1] + A.a[2] * x[2], A.a[3] * x[0] + A.a[4] * x[1] + A.a[5] * x[2],
           A.a[6] * x[0] + A.a[7] * x[1] + A.a[8] * x[2]}};
}
inline Mat3 transpose(const Mat3& A) {
  Mat3 T;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) T.a[3 * i + j] = A.a[3 * j + i];
  return T;
}
/// A^T B without forming the transpose.
inline Mat3 transpose_times(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C.a[3 * i + j] = A.a[i] * B.a[j] + A.a[3 + i] * B.a[3 + j] + A.a[6 + i] * B.a[6 + j];
  return C;
}
/// A B^T without forming the transpose.
inline Mat3 times_transpose(const Mat3& A, const Mat3& B) {
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      C.a[3 * i + j] = A.a[3 * i] * B.a[3 * j] + A.a[3 * i + 1] * B.a[3 * j + 1] + A.a[3 * i + 2] * B.a[3 * j + 2];
  return C;
}
/// Q A Q^T (rotation of a tensor into the spatial frame).
inline Mat3 rotate(const Mat3& Q, const Mat3& A) { return times_transpose(Q * A, Q); }
/// Q^T A Q (rotation of a tensor into the unrotated frame, thesis eq. 2.6).
inline Mat3 unrotate(const Mat3& Q, const Mat3& A) { return transpose_times(Q, A * Q); }
/// Q S Q^T for symmetric S: only the upper triangle is computed (result exactly symmetric).
inline Mat3 rotate_sym(const Mat3& Q, const Mat3& S) {
  const Mat3 B = Q * S;
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const double c = B.a[3 * i] * Q.a[3 * j] + B.a[3 * i + 1] * Q.a[3 * j + 1] + B.a[3 * i + 2] * Q.a[3 * j + 2];
      C.a[3 * i + j] = c;
      C.a[3 * j + i] = c;
    }
  return C;
}
/// Q^T S Q for symmetric S: only the upper triangle is computed (result exactly symmetric).
inline Mat3 unrotate_sym(const Mat3& Q, const Mat3& S) {
  const Mat3 B = S * Q;
  Mat3 C;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      const double c = Q.a[i] * B.a[j] + Q.a[3 + i] * B.a[3 + j] + Q.a[6 + i] * B.a[6 + j];
      C.a[3 * i + j] = c;
      C.a[3 * j + i] = c;
    }
  return C;
}

inline double trace(const Mat3& A) { return A.a[0] + A.a[4] + A.a[8]; }
inline double ddot(const Mat3& A, const Mat3& B) {
  double s = 0;
  for (int k = 0; k < 9; ++k) s += A.a[k] * B.a[k];
  return s;
}
inline double frobenius(const Mat3& A) { return std::sqrt(ddot(A, A)); }
inline Mat3 sym(const Mat3& A) { return 0.5 * (A + transpose(A)); }
inline Mat3 skew(const Mat3& A) { return 0.5 * (A - transpose(A)); }
inline Mat3 deviator(const Mat3& A) {
  Mat3 D = A;
  const double m = trace(A) / 3.0;
  D.a[0] -= m; D.a[4] -= m; D.a[8] -= m;
  return D;
}
inline double det(const Mat3& A) {
  return A.a[0] * (A.a[4] * A.a[8] - A.a[5] * A.a[7]) - A.a[1] * (A.a[3] * A.a[8] - A.a[5] * A.a[6]) +
         A.a[2] * (A.a[3] * A.a[7] - A.a[4] * A.a[6]);
}
/// Cofactor matrix: cof(A) = det(A) A^{-T}; well defined for singular A.
inline Mat3 cofactor(const Mat3& A) {
  Mat3 C;
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
/// Inverse; the caller guarantees det(A) != 0.
inline Mat3 inverse(const Mat3& A) { return (1.0 / det(A)) * transpose(cofactor(A)); }
/// A^{-T} = cof(A)/det(A).
inline Mat3 inverse_transpose(const Mat3& A) { return (1.0 / det(A)) * cofactor(A); }

/// von Mises equivalent stress sqrt(3 J2).
inline double von_mises(const Mat3& s) {
  const Mat3 d = deviator(s);
  return std::sqrt(1.5 * ddot(d, d));
}

/// Rotation by angle (rad) about a unit axis (Rodrigues' formula).
inline Mat3 rotation_about(const Vec3& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  const double x = axis[0], y = axis[1], z = axis[2];
  Mat3 R;
  R.a[0] = t * x * x + c;     R.a[1] = t * x * y - s * z; R.a[2] = t * x * z + s * y;
  R.a[3] = t * x * y + s * z; R.a[4] = t * y * y + c;     R.a[5] = t * y * z - s * x;
  R.a[6] = t * x * z - s * y; R.a[7] = t * y * z + s * x; R.a[8] = t * z * z + c;
  return R;
}

inline bool all_finite(const Mat3& A) {
  for (double x : A.a) if (!std::isfinite(x)) return false;
  return true;
}
inline bool all_finite(const Vec3& x) { return std::isfinite(x[0]) && std::isfinite(x[1]) && std::isfinite(x[2]); }

}  // namespace ballista
