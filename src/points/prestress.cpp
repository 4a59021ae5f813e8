#include "points/prestress.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/point_fields.hpp"
#include "materials/point_batch.hpp"

namespace ballista {

namespace {

// Load increments along the proportional path, and the time each takes: slow enough that a
// rate-dependent model answers as at rest (the overburden is applied over hours, not microseconds).
constexpr int kIncrements = 20;
constexpr double kIncrementTime = 1.0e-3;  // s
constexpr int kMaxNewton = 30;
// Finite-difference step of the Jacobian d sigma / d(log stretch): small against the strains of an
// overburden (1e-3) and large against round-off of stresses of order K * 1e-3.
constexpr double kStrainStep = 1.0e-7;

/// The committed state of the driven point, and four trials from it (the increment and its three
/// perturbations), updated together.
class DrivenPoint {
 public:
  explicit DrivenPoint(const Material& m) : committed_(m, 1), trials_(m, 4) {}

  /// The principal stresses of trial j after the log-stretch increment e[j] from the committed state.
  void evaluate(const std::array<Vec3, 4>& e, std::array<Vec3, 4>& stress) {
    for (Index j = 0; j < 4; ++j) {
      trials_.copy_point(committed_, 0, j);
      const Mat3 dF = Mat3::diag(std::exp(e[j][0]), std::exp(e[j][1]), std::exp(e[j][2]));
      trials_.F_old(j) = committed_.F(0);
      trials_.F(j) = dF * committed_.F(0);
      trials_.L(j) = (1.0 / kIncrementTime) * (dF - Mat3::identity());
    }
    trials_.step(kIncrementTime);
    for (Index j = 0; j < 4; ++j) {
      const Mat3& S = trials_.stress(j);
      stress[j] = Vec3{{S(0, 0), S(1, 1), S(2, 2)}};
    }
  }

  void commit(Index j) { committed_.copy_point(trials_, j, 0); }

  /// Copies the committed state to the points [first, last) of `points` (same model's fields).
  void copy_to(FieldStore& points, Index first, Index last) {
    Mat3* F = points.view(kDeformationGradient);
    Mat3* R = points.view(kRotation);
    Mat3* S = points.view(kStress);
    const std::vector<std::string>& names = committed_.state_names();
    std::vector<double*> fields;
    for (const std::string& n : names) fields.push_back(points.real(n));
    for (Index p = first; p < last; ++p) {
      F[p] = committed_.F(0);
      R[p] = committed_.R(0);
      S[p] = committed_.stress(0);
      for (size_t k = 0; k < fields.size(); ++k) fields[k][p] = committed_.state(static_cast<int>(k), 0);
    }
  }

  Mat3 F() { return committed_.F(0); }

 private:
  PointBatch committed_;
  PointBatch trials_;
};

double max_abs(const Vec3& v) { return std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])}); }

}  // namespace

void apply_prestress(const Material& material, const Vec3& stress, Dimension dim, FieldStore& points, Index first,
                     Index last) {
  const double scale = max_abs(stress);
  if (scale == 0.0) return;
  // Converged when every principal stress is within this of its target: round-off of the model's
  // own update, far below anything a damped stage would resolve (its band is 5 %).
  const double tol = 1.0e-9 * scale;
  DrivenPoint pt(material);
  Vec3 e{};  // log-stretch increment of the last increment: the next one's first guess
  for (int k = 1; k <= kIncrements; ++k) {
    const Vec3 target = (static_cast<double>(k) / kIncrements) * stress;
    bool converged = false;
    Vec3 residual{};
    for (int it = 0; it < kMaxNewton && !converged; ++it) {
      std::array<Vec3, 4> trial{e, e, e, e};
      for (int j = 0; j < 3; ++j) trial[static_cast<size_t>(j + 1)][j] += kStrainStep;
      std::array<Vec3, 4> s;
      pt.evaluate(trial, s);
      residual = s[0] - target;
      if (!std::isfinite(max_abs(residual))) break;
      if (max_abs(residual) <= tol) {
        pt.commit(0);
        converged = true;
        break;
      }
      Mat3 J;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) J(i, j) = (s[static_cast<size_t>(j + 1)][i] - s[0][i]) / kStrainStep;
      const double d = det(J);
      if (!(std::abs(d) > 0.0) || !std::isfinite(d)) break;
      e = e - inverse(J) * residual;
    }
    if (!converged)
      throw std::runtime_error(fmt::format(
          "material '{}' ({}) cannot be prestressed to [{:g}, {:g}, {:g}] Pa: at {:g} % of it its stress is {:g} Pa "
          "from the target after {} iterations (beyond its strength?)",
          material.name(), material.model(), stress[0], stress[1], stress[2], 100.0 * k / kIncrements,
          max_abs(residual), kMaxNewton));
  }
  const Mat3 F = pt.F();
  pt.copy_to(points, first, last);

  // Positions and volumes follow the uniform deformation, about the centre of mass (the axis in
  // axisymmetric runs, where F's hoop stretch is r / r0).
  Vec3* x = points.view(kPosition);
  const double* mass = points.real(kMass);
  double* volume = points.real(kVolume);
  const double* volume0 = points.real(kReferenceVolume);
  Vec3 c{};
  double m = 0.0;
  for (Index p = first; p < last; ++p) {
    c += mass[p] * x[p];
    m += mass[p];
  }
  if (m > 0.0) c = (1.0 / m) * c;
  if (dim == Dimension::Axisymmetric) c[0] = 0.0;
  if (dim != Dimension::ThreeD) c[2] = 0.0;
  const double J = det(F);
  for (Index p = first; p < last; ++p) {
    Vec3 moved = c + F * (x[p] - c);
    if (dim != Dimension::ThreeD) moved[2] = x[p][2];
    x[p] = moved;
    volume[p] = J * volume0[p];
  }
}

}  // namespace ballista
