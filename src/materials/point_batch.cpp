#include "materials/point_batch.hpp"

#include <numeric>

#include "core/point_fields.hpp"

namespace ballista {

namespace {
/// F at the start of the step the batch drives (1).
constexpr FieldKey<Mat3> kOldDeformationGradient{"F_old"};
}  // namespace

PointBatch::PointBatch(const Material& m, Index n) : m_(m), n_(n) {
  store_.declare(kDeformationGradient, "1");
  store_.declare(kOldDeformationGradient, "1");
  store_.declare(kVelocityGradient, "1/s");
  store_.declare(kRotation, "1");
  store_.declare(kStress, "Pa");
  m.declare_fields(store_);
  store_.resize(n);
  F_ = store_.view(kDeformationGradient);
  F_old_ = store_.view(kOldDeformationGradient);
  L_ = store_.view(kVelocityGradient);
  R_ = store_.view(kRotation);
  stress_ = store_.view(kStress);
  for (const StateFieldSpec& s : m.state_fields()) {
    state_names_.push_back(s.name);
    state_.push_back(store_.real(s.name));
    for (Index p = 0; p < n; ++p) state_.back()[p] = s.initial;
  }
  for (Index p = 0; p < n; ++p) {
    F_[p] = F_old_[p] = R_[p] = Mat3::identity();
    L_[p] = stress_[p] = Mat3{};
  }
  all_.resize(static_cast<size_t>(n));
  std::iota(all_.begin(), all_.end(), Index{0});
}

void PointBatch::set_F_eq410(Index p, const Mat3& F_new, double dt) {
  F_old_[p] = F_[p];
  F_[p] = F_new;
  L_[p] = (1.0 / dt) * (F_new * inverse(F_old_[p]) - Mat3::identity());
}

void PointBatch::step(double dt, double* tangent) {
  MaterialBatch b;
  b.points = all_.data();
  b.count = n_;
  b.F_old = F_old_;
  b.F_new = F_;
  b.L = L_;
  b.R = R_;
  b.stress = stress_;
  b.store = &store_;
  b.dt = dt;
  b.tangent = tangent;
  m_.update(b);
}

void PointBatch::copy_point(const PointBatch& src, Index from, Index to) {
  F_[to] = src.F_[from];
  F_old_[to] = src.F_old_[from];
  R_[to] = src.R_[from];
  stress_[to] = src.stress_[from];
  for (size_t s = 0; s < state_.size(); ++s) state_[s][to] = src.state_[s][from];
}

}  // namespace ballista
