#include "verify/point_batch.hpp"

#include <numeric>

namespace ballista {

PointBatch::PointBatch(const Material& m, Index n) : m_(m), n_(n) {
  store_.add_real("F", 9, "1");
  store_.add_real("F_old", 9, "1");
  store_.add_real("L", 9, "1/s");
  store_.add_real("R", 9, "1");
  store_.add_real("stress", 9, "Pa");
  m.declare_fields(store_);
  store_.resize(n);
  F_ = store_.view<Mat3>("F");
  F_old_ = store_.view<Mat3>("F_old");
  L_ = store_.view<Mat3>("L");
  R_ = store_.view<Mat3>("R");
  stress_ = store_.view<Mat3>("stress");
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
