#pragma once
// Seeded random deformation paths and rotations for the A6 checks (verification CATALOGUE A6).
// The generator is spelled out (mt19937_64 bits -> [0, 1)) so that the paths are the same with
// every standard library.
#include <cstdint>
#include <random>
#include <vector>

#include "core/tensor.hpp"

namespace ballista {

struct A6Problem {
  std::uint64_t seed = 20240611;  ///< fixed: the report is reproducible
  int paths = 3;                  ///< independent random F paths
  int segments = 4;               ///< straight pieces of each path (load, unload, reload ...)
  int steps_per_segment = 50;
  /// Entries of F - I at the waypoints are uniform in [-amplitude, amplitude]: a 4 % general
  /// deformation (stretch, shear, volume change, rotation), well past yield for metal examples.
  double amplitude = 0.04;
  double duration = 1e-3;         ///< s (strain rates ~100/s: inside every model's range)
  int constant_rotations = 2;     ///< copies of each path under a fixed random rotation
  int rotating_copies = 2;        ///< copies under a random rotation that turns 0.5-2 turns over the path
  int tangent_checks_per_path = 4;
  double fd_step = 1e-7;          ///< central-difference strain step (see a6_tangent.cpp)

  int steps() const { return segments * steps_per_segment; }
  double dt() const { return duration / steps(); }
};

/// Uniform [0, 1) from the top 53 bits of a 64-bit Mersenne twister.
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
inline double uniform(std::mt19937_64& rng, double lo, double hi) { return lo + (hi - lo) * uniform01(rng); }

/// A unit vector, uniformly distributed on the sphere (rejection from the cube).
inline Vec3 random_axis(std::mt19937_64& rng) {
  for (;;) {
    Vec3 a{{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}};
    const double n = norm(a);
    if (n > 0.1 && n <= 1.0) return (1.0 / n) * a;
  }
}

/// Piecewise-linear F(t) through random waypoints F_0 = I, F_k = I + A_k.
struct RandomFPath {
  std::vector<Mat3> waypoints;
  int steps_per_segment = 1;
  /// F after `step` steps (step in [0, segments * steps_per_segment]).
  Mat3 at_step(int step) const {
    const int k = step / steps_per_segment, j = step % steps_per_segment;
    if (k >= static_cast<int>(waypoints.size()) - 1) return waypoints.back();
    const double tau = static_cast<double>(j) / steps_per_segment;
    return waypoints[k] + tau * (waypoints[k + 1] - waypoints[k]);
  }
};

inline RandomFPath random_F_path(std::mt19937_64& rng, const A6Problem& pb) {
  RandomFPath p;
  p.steps_per_segment = pb.steps_per_segment;
  p.waypoints.push_back(Mat3::identity());
  for (int k = 0; k < pb.segments; ++k) {
    Mat3 F = Mat3::identity();
    for (double& x : F.a) x += uniform(rng, -pb.amplitude, pb.amplitude);
    p.waypoints.push_back(F);
  }
  return p;
}

/// A superimposed rotation Q(t) = Rot(axis, angle0 + rate t) (rate 0 for a constant one).
struct RandomRotation {
  Vec3 axis{{0.0, 0.0, 1.0}};
  double angle0 = 0.0;
  double rate = 0.0;  ///< rad/s
  Mat3 at(double t) const { return rotation_about(axis, angle0 + rate * t); }
};

inline RandomRotation random_rotation(std::mt19937_64& rng, double duration, bool rotating) {
  RandomRotation r;
  r.axis = random_axis(rng);
  r.angle0 = uniform(rng, -3.14159, 3.14159);
  if (rotating) r.rate = uniform(rng, 3.14159, 4 * 3.14159) / duration * (uniform01(rng) < 0.5 ? -1.0 : 1.0);
  return r;
}

}  // namespace ballista
