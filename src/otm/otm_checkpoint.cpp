// Checkpoint and restart of the OTM solver (issue 16, docs/restart.md). The supports are stored,
// not rebuilt: the LME solves are warm-started from the multipliers of the previous build, so a
// rebuild at restart would converge to the same functions only to within the solver tolerance.
#include <cstring>

#include "otm/otm_solver.hpp"

namespace ballista {

namespace {

template <class T>
std::vector<double> flatten(const std::vector<T>& v) {
  constexpr std::size_t k = sizeof(T) / sizeof(double);
  std::vector<double> out(k * v.size());
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size() * sizeof(double));
  return out;
}

template <class T>
void unflatten(const std::vector<double>& in, std::vector<T>& out) {
  constexpr std::size_t k = sizeof(T) / sizeof(double);
  out.resize(in.size() / k);
  if (!out.empty()) std::memcpy(out.data(), in.data(), out.size() * sizeof(T));
}

template <class T>
std::vector<std::int64_t> as_ints(const std::vector<T>& v) {
  return std::vector<std::int64_t>(v.begin(), v.end());
}

template <class T>
void from_ints(const std::vector<std::int64_t>& in, std::vector<T>& out) {
  out.assign(in.begin(), in.end());
}

void put_supports(StateArchive& a, const std::string& prefix, const otm::Supports& s) {
  a.put(prefix + "offset", as_ints(s.offset));
  a.put(prefix + "node", as_ints(s.node));
  a.put(prefix + "N", s.N);
  a.put(prefix + "dN", flatten(s.dN));
}

void get_supports(const StateArchive& a, const std::string& prefix, otm::Supports& s) {
  from_ints(a.ints(prefix + "offset"), s.offset);
  from_ints(a.ints(prefix + "node"), s.node);
  s.N = a.reals(prefix + "N", s.node.size());
  unflatten(a.reals(prefix + "dN", 3 * s.node.size()), s.dN);
}

}  // namespace

void OtmSolver::save_state(StateArchive& a) const {
  pts_.save_state(a);
  a.put_real("otm.time", time_);
  a.put_int("otm.steps", steps_);
  a.put("otm.scalars", std::vector<double>{damping_, dt_prev_, external_work_, damping_work_, wall_work_, wall_force_,
                                           remap_work_, momentum0_[0], momentum0_[1], momentum0_[2], mean_support_,
                                           max_condition_});
  a.put("otm.counters", std::vector<std::int64_t>{next_id_, static_cast<std::int64_t>(splits_),
                                                  static_cast<std::int64_t>(regenerations_), max_support_,
                                                  max_iterations_, static_cast<std::int64_t>(fallbacks_),
                                                  static_cast<std::int64_t>(retries_)});
  a.put("otm.nodes.x", flatten(nodes_.x));
  a.put("otm.nodes.v", flatten(nodes_.v));
  a.put("otm.nodes.f", flatten(nodes_.f));
  a.put("otm.nodes.mass", nodes_.mass);
  a.put("otm.nodes.body", nodes_.body);
  put_supports(a, "otm.supports.", sup_);
  put_supports(a, "otm.previous_supports.", prev_sup_);
  a.put("otm.lambda", flatten(lambda_));
  a.put("otm.scale", scale_);
  a.put("otm.Fr", flatten(Fr_));
  a.put("otm.interpolated", as_ints(interpolated_));
}

void OtmSolver::load_state(const StateArchive& a) {
  pts_.load_state(a);
  time_ = a.real("otm.time");
  steps_ = static_cast<long>(a.integer("otm.steps"));
  const auto& s = a.reals("otm.scalars", 12);
  damping_ = s[0];
  dt_prev_ = s[1];
  external_work_ = s[2];
  damping_work_ = s[3];
  wall_work_ = s[4];
  wall_force_ = s[5];
  remap_work_ = s[6];
  momentum0_ = Vec3{{s[7], s[8], s[9]}};
  mean_support_ = s[10];
  max_condition_ = s[11];
  const auto& c = a.ints("otm.counters", 7);
  next_id_ = c[0];
  splits_ = static_cast<Index>(c[1]);
  regenerations_ = static_cast<Index>(c[2]);
  max_support_ = static_cast<int>(c[3]);
  max_iterations_ = static_cast<int>(c[4]);
  fallbacks_ = static_cast<Index>(c[5]);
  retries_ = static_cast<Index>(c[6]);
  unflatten(a.reals("otm.nodes.x"), nodes_.x);
  const std::size_t nn = nodes_.x.size();
  unflatten(a.reals("otm.nodes.v", 3 * nn), nodes_.v);
  unflatten(a.reals("otm.nodes.f", 3 * nn), nodes_.f);
  nodes_.mass = a.reals("otm.nodes.mass", nn);
  nodes_.body = a.ints("otm.nodes.body", nn);
  get_supports(a, "otm.supports.", sup_);
  get_supports(a, "otm.previous_supports.", prev_sup_);
  const std::size_t n = static_cast<std::size_t>(points_.size());
  unflatten(a.reals("otm.lambda", 3 * n), lambda_);
  scale_ = a.reals("otm.scale");
  unflatten(a.reals("otm.Fr"), Fr_);
  from_ints(a.ints("otm.interpolated"), interpolated_);
  otm::build_influences(sup_, nodes_.size(), inf_);
}

}  // namespace ballista
