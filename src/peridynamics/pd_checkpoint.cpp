// Checkpoint and restart of the peridynamic solver (issue 16, docs/restart.md): what a step
// carries to the next beyond the point fields. Everything the constructor derives from the deck
// (bond families, constants, blocks, mirrors) is rebuilt identically and is only checked here.
#include "core/error.hpp"
#include "peridynamics/pd_solver.hpp"

namespace ballista {

void PdSolver::save_state(StateArchive& a) const {
  pts_.save_state(a);
  a.put_real("pd.time", time_);
  a.put_int("pd.steps", steps_);
  a.put("pd.scalars", std::vector<double>{external_work_, damping_, next_fragment_time_});
  a.put("pd.counters", std::vector<std::int64_t>{static_cast<std::int64_t>(vented_count_),
                                                 static_cast<std::int64_t>(gas_rate_limited_)});
  a.put_integers("pd.bond_broken", bonds_.broken);
  a.put("pd.plastic_stretch", sp_);
  a.put("pd.critical_stretch", s0_);
  a.put("pd.dissipated", dissipated_);
  a.put("pd.contact_energy", contact_energy_);
  a.put("pd.contact_stiffness", stiff_contact_);
  a.put_integers("pd.contact.offset", contact_.offset);
  a.put_integers("pd.contact.other", contact_.other);
  a.put("pd.contact.reach", contact_.reach);
  a.put_records("pd.contact.x_build", contact_.x_build);
  a.put("pd.contact.state", std::vector<double>{contact_.skin, static_cast<double>(contact_.builds)});
  a.put("pd.gas.x", gas_x_);
  a.put("pd.gas.g", gas_g_);
  a.put_integers("pd.gas.vented", vented_);
  a.put_records("pd.gas.vent_velocity", vent_velocity_);
  std::vector<double> rows;
  const std::size_t width = fragment_rows_.empty() ? 0 : fragment_rows_.front().size();
  for (const auto& r : fragment_rows_) rows.insert(rows.end(), r.begin(), r.end());
  a.put("pd.fragment_rows", rows);
  a.put_int("pd.fragment_row_width", static_cast<std::int64_t>(width));
}

void PdSolver::load_state(const StateArchive& a) {
  pts_.load_state(a);
  if (points_.size() != bonds_.points())
    throw Error("the checkpoint holds " + std::to_string(points_.size()) + " peridynamic points, this deck seeds " +
                std::to_string(bonds_.points()));
  time_ = a.real("pd.time");
  steps_ = static_cast<long>(a.integer("pd.steps"));
  const auto& sc = a.reals("pd.scalars", 3);
  external_work_ = sc[0];
  damping_ = sc[1];
  next_fragment_time_ = sc[2];
  const auto& cn = a.ints("pd.counters", 2);
  vented_count_ = static_cast<Index>(cn[0]);
  gas_rate_limited_ = static_cast<Index>(cn[1]);
  a.get_integers("pd.bond_broken", bonds_.broken, bonds_.broken.size());
  sp_ = a.reals("pd.plastic_stretch", sp_.size());
  s0_ = a.reals("pd.critical_stretch", s0_.size());
  dissipated_ = a.reals("pd.dissipated", dissipated_.size());
  contact_energy_ = a.reals("pd.contact_energy", contact_energy_.size());
  stiff_contact_ = a.reals("pd.contact_stiffness", stiff_contact_.size());
  a.get_integers("pd.contact.offset", contact_.offset);
  a.get_integers("pd.contact.other", contact_.other);
  contact_.reach = a.reals("pd.contact.reach", contact_.other.size());
  a.get_records("pd.contact.x_build", contact_.x_build);
  const auto& cs = a.reals("pd.contact.state", 2);
  contact_.skin = cs[0];
  contact_.builds = static_cast<long>(cs[1]);
  gas_x_ = a.reals("pd.gas.x", gas_x_.size());
  gas_g_ = a.reals("pd.gas.g", gas_g_.size());
  a.get_integers("pd.gas.vented", vented_, vented_.size());
  a.get_records("pd.gas.vent_velocity", vent_velocity_);
  const auto width = static_cast<std::size_t>(a.integer("pd.fragment_row_width"));
  const auto& rows = a.reals("pd.fragment_rows");
  fragment_rows_.clear();
  for (std::size_t at = 0; width > 0 && at + width <= rows.size(); at += width)
    fragment_rows_.emplace_back(rows.begin() + static_cast<std::ptrdiff_t>(at),
                                rows.begin() + static_cast<std::ptrdiff_t>(at + width));
  loads_current_ = false;  // the loads at the restored positions are computed at the next step
}

}  // namespace ballista
