// Checkpoint and restart of the OTM solver (docs/restart.md). The supports are stored,
// not rebuilt: the LME solves are warm-started from the multipliers of the previous build, so a
// rebuild at restart would converge to the same functions only to within the solver tolerance.
#include "otm/otm_solver.hpp"

namespace ballista {

namespace {

void put_supports(StateArchive& a, const std::string& prefix, const otm::Supports& s) {
  a.put_integers(prefix + "offset", s.offset);
  a.put_integers(prefix + "node", s.node);
  a.put(prefix + "N", s.N);
  a.put_records(prefix + "dN", s.dN);
}

void get_supports(const StateArchive& a, const std::string& prefix, otm::Supports& s) {
  a.get_integers(prefix + "offset", s.offset);
  a.get_integers(prefix + "node", s.node);
  s.N = a.reals(prefix + "N", s.node.size());
  a.get_records(prefix + "dN", s.dN, s.node.size());
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
  if (contact_) a.put_real("otm.contact_work", contact_work_);
  a.put_records("otm.nodes.x", nodes_.x);
  a.put_records("otm.nodes.v", nodes_.v);
  a.put_records("otm.nodes.f", nodes_.f);
  a.put("otm.nodes.mass", nodes_.mass);
  a.put("otm.nodes.body", nodes_.body);
  put_supports(a, "otm.supports.", sup_);
  put_supports(a, "otm.previous_supports.", prev_sup_);
  a.put_records("otm.lambda", lambda_);
  a.put("otm.scale", scale_);
  a.put_records("otm.Fr", Fr_);
  a.put_integers("otm.interpolated", interpolated_);
}

void OtmSolver::load_state(const StateArchive& a) {
  pts_.load_state(a);
  time_ = a.real("otm.time");
  steps_ = static_cast<long>(a.integer("otm.steps"));
  a.get_into("otm.scalars", {&damping_, &dt_prev_, &external_work_, &damping_work_, &wall_work_, &wall_force_,
                             &remap_work_, &momentum0_[0], &momentum0_[1], &momentum0_[2], &mean_support_,
                             &max_condition_});
  a.get_integers_into("otm.counters", next_id_, splits_, regenerations_, max_support_, max_iterations_, fallbacks_,
                      retries_);
  if (contact_) contact_work_ = a.real("otm.contact_work");
  a.get_records("otm.nodes.x", nodes_.x);
  const std::size_t nn = nodes_.x.size();
  a.get_records("otm.nodes.v", nodes_.v, nn);
  a.get_records("otm.nodes.f", nodes_.f, nn);
  nodes_.mass = a.reals("otm.nodes.mass", nn);
  nodes_.body = a.ints("otm.nodes.body", nn);
  get_supports(a, "otm.supports.", sup_);
  get_supports(a, "otm.previous_supports.", prev_sup_);
  const std::size_t n = static_cast<std::size_t>(points_.size());
  a.get_records("otm.lambda", lambda_, n);
  scale_ = a.reals("otm.scale");
  a.get_records("otm.Fr", Fr_);
  a.get_integers("otm.interpolated", interpolated_);
  otm::build_influences(sup_, nodes_.size(), inf_);
}

}  // namespace ballista
