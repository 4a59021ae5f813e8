// Checkpoint and restart of the peridynamic solver (docs/restart.md): what a step
// carries to the next beyond the point fields. Everything the constructor derives from the deck
// (bond families, constants, blocks, mirrors, the partition) is rebuilt identically. Per-point
// values and bond rows are written in the points' order of the checkpoint (rank order on several
// ranks, gathered to rank 0); a point's row is its whole family in id order of the other ends, the
// same on any rank count, so a checkpoint restarts on any number of ranks.
#include <algorithm>

#include "core/error.hpp"
#include "peridynamics/pd_solver.hpp"
#include "points/point_exchange.hpp"

namespace ballista {

void PdSolver::save_state(StateArchive& a) const {
  pts_.save_state(a);  // collective: rank 0's archive holds every rank's points
  const auto& own = local_.own;
  const bool contacts_built = params_.contact && contact_.builds > 0;
  // Each own point's value, or bond row, gathered to rank 0 in the store's order.
  auto gathered = [&](std::vector<double> mine) {
    return comm_.distributed() ? gather_values(comm_, mine) : mine;
  };
  auto per_point = [&](const std::vector<double>& v) {
    std::vector<double> out;
    out.reserve(own.size());
    for (Index l : own) out.push_back(v[l]);
    return gathered(std::move(out));
  };
  std::vector<double> row_length, broken, plastic, deviatoric, x_build;
  for (Index l : own) {
    row_length.push_back(static_cast<double>(bonds_.offset[l + 1] - bonds_.offset[l]));
    for (Index k = bonds_.offset[l]; k < bonds_.offset[l + 1]; ++k) {
      broken.push_back(bonds_.broken[k]);
      if (!sp_.empty()) plastic.push_back(sp_[k]);
      if (!lps_td_.empty()) deviatoric.push_back(lps_td_[k]);
    }
    if (contacts_built) x_build.insert(x_build.end(), contact_.x_build[l].v, contact_.x_build[l].v + 3);
  }
  row_length = gathered(std::move(row_length));
  broken = gathered(std::move(broken));
  plastic = gathered(std::move(plastic));
  deviatoric = gathered(std::move(deviatoric));
  x_build = gathered(std::move(x_build));
  const std::vector<double> s0 = per_point(s0_), dissipated = per_point(dissipated_),
                            contact_energy = per_point(contact_energy_), stiffness = per_point(stiff_contact_);
  // The products (per own point; empty without gas).
  std::vector<double> gas_x, gas_g, vented, vent_velocity;
  if (has_gas_) {
    gas_x = per_point(gas_x_);
    gas_g = per_point(gas_g_);
    std::vector<double> flag, vel;
    for (Index l : own) {
      flag.push_back(vented_[l]);
      vel.insert(vel.end(), vent_velocity_[l].v, vent_velocity_[l].v + 3);
    }
    vented = gathered(std::move(flag));
    vent_velocity = gathered(std::move(vel));
  }
  // The inputs of the last renewal of the gas family (one rank only: pd_gas.cpp): a restart builds
  // the same family from them.
  std::vector<double> renewal;
  if (!renewal_.x.empty())
    for (Index l : own) {
      renewal.insert(renewal.end(), renewal_.x[l].v, renewal_.x[l].v + 3);
      renewal.push_back(renewal_.X[l]);
      renewal.push_back(renewal_.skip[l]);
    }
  // Counters: each rank's (a restart on as many ranks takes its own back) and the totals (the
  // contact ghosts' offered bytes are per rank only: they depend on the decomposition).
  const std::vector<double> counts{static_cast<double>(vented_count_), static_cast<double>(gas_rate_limited_),
                                   static_cast<double>(halo_.offered_bytes())};
  const std::vector<double> counts_by_rank = gathered(counts);
  std::vector<double> totals(counts.begin(), counts.begin() + 2);
  comm_.sum(totals.data(), static_cast<int>(totals.size()));
  const bool vented_since_build = comm_.any(vented_since_build_);
  if (comm_.rank() != 0) return;
  a.put_real("pd.time", time_);
  a.put_int("pd.steps", steps_);
  a.put("pd.scalars", std::vector<double>{external_work_, damping_, next_fragment_time_});
  a.put("pd.counters", std::vector<std::int64_t>(totals.begin(), totals.end()));
  a.put("pd.counters_by_rank", std::vector<std::int64_t>(counts_by_rank.begin(), counts_by_rank.end()));
  a.put("pd.row_length", std::vector<std::int64_t>(row_length.begin(), row_length.end()));
  a.put("pd.bond_broken", std::vector<std::int64_t>(broken.begin(), broken.end()));
  a.put("pd.plastic_stretch", plastic);
  // The state-based plasticity's deviatoric force state of the last evaluation (its plastic work
  // of the next step, lps_pass.hpp).
  if (!lps_td_.empty()) a.put("pd.lps_deviatoric_force", deviatoric);
  a.put("pd.critical_stretch", s0);
  a.put("pd.dissipated", dissipated);
  a.put("pd.contact_energy", contact_energy);
  a.put("pd.contact_stiffness", stiffness);
  a.put("pd.contact.x_build", x_build);
  a.put("pd.contact.state", std::vector<double>{contact_.skin, static_cast<double>(contact_.builds)});
  a.put_int("pd.contact.vented_since_build", vented_since_build ? 1 : 0);
  a.put("pd.gas.x", gas_x);
  a.put("pd.gas.g", gas_g);
  a.put("pd.gas.vented", std::vector<std::int64_t>(vented.begin(), vented.end()));
  a.put("pd.gas.vent_velocity", vent_velocity);
  if (!renewal.empty()) {
    a.put("pd.gas.renewal", renewal);
    a.put_int("pd.gas.renewals", gas_renewals_);
  }
  std::vector<double> rows;
  const std::size_t width = fragment_rows_.empty() ? 0 : fragment_rows_.front().size();
  for (const auto& r : fragment_rows_) rows.insert(rows.end(), r.begin(), r.end());
  a.put("pd.fragment_rows", rows);
  a.put_int("pd.fragment_row_width", static_cast<std::int64_t>(width));
}

void PdSolver::load_state(const StateArchive& a) {
  // This rank's points (the deck's partition) back from the checkpoint, in id order.
  const Index n = static_cast<Index>(local_.own.size());
  std::vector<std::int64_t> ids(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) ids[i] = local_.id[local_.own[i]];
  pts_.load_state(a, ids);
  if (points_.size() != n)
    throw Error("the checkpoint holds " + std::to_string(points_.size()) + " peridynamic points, this deck seeds " +
                std::to_string(n));
  // Where each own point sits in the checkpoint's order, and where its row starts.
  const auto& saved_id = a.ints("points.id");
  const auto m = saved_id.size();
  std::vector<std::pair<std::int64_t, std::size_t>> by_id(m);
  for (std::size_t j = 0; j < m; ++j) by_id[j] = {saved_id[j], j};
  std::sort(by_id.begin(), by_id.end());
  const auto& length = a.ints("pd.row_length", m);
  std::vector<std::size_t> row_start(m + 1, 0);
  for (std::size_t j = 0; j < m; ++j) row_start[j + 1] = row_start[j] + static_cast<std::size_t>(length[j]);
  const auto& broken = a.ints("pd.bond_broken", row_start[m]);
  const auto& plastic = a.reals("pd.plastic_stretch", sp_.empty() ? 0 : row_start[m]);
  static const std::vector<double> kNoDeviatoric;
  const auto& deviatoric = lps_td_.empty() ? kNoDeviatoric : a.reals("pd.lps_deviatoric_force", row_start[m]);
  const auto& s0 = a.reals("pd.critical_stretch", m);
  const auto& dissipated = a.reals("pd.dissipated", m);
  const auto& contact_energy = a.reals("pd.contact_energy", m);
  const auto& stiffness = a.reals("pd.contact_stiffness", m);
  double skin = 0.0, build_count = 0.0;
  a.get_into("pd.contact.state", {&skin, &build_count});
  const long builds = static_cast<long>(build_count);
  const bool contacts_built = params_.contact && builds > 0;
  const auto& x_build = a.reals("pd.contact.x_build", contacts_built ? 3 * m : 0);
  const auto& gas_x = a.reals("pd.gas.x", has_gas_ ? m : 0);
  const auto& gas_g = a.reals("pd.gas.g", has_gas_ ? m : 0);
  const auto& vented = a.ints("pd.gas.vented", has_gas_ ? m : 0);
  const auto& vent_velocity = a.reals("pd.gas.vent_velocity", has_gas_ ? 3 * m : 0);
  const bool renewed = a.has("pd.gas.renewal");
  if (renewed && comm_.distributed())
    throw Error("the checkpoint's gas family was renewed in the current configuration "
                "(peridynamics.gas_refamily_steps): restart it on one MPI rank");
  static const std::vector<double> kNone;
  const auto& renewal = renewed ? a.reals("pd.gas.renewal", 5 * m) : kNone;
  if (renewed) {
    renewal_.x.assign(static_cast<size_t>(local_.size()), Vec3{});
    renewal_.X.assign(static_cast<size_t>(local_.size()), 1.0);
    renewal_.skip.assign(static_cast<size_t>(local_.size()), 0);
  }
  for (Index i = 0; i < n; ++i) {
    const Index l = local_.own[i];
    const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair<std::int64_t, std::size_t>{ids[i], 0});
    if (it == by_id.end() || it->first != ids[i])
      throw Error("the checkpoint lacks peridynamic point " + std::to_string(ids[i]));
    const std::size_t j = it->second;
    const Index k0 = bonds_.offset[l], len = bonds_.offset[l + 1] - k0;
    if (len != length[j])
      throw Error("point " + std::to_string(ids[i]) + " has " + std::to_string(len) + " bonds in this deck, " +
                  std::to_string(length[j]) + " in the checkpoint");
    for (Index k = 0; k < len; ++k) {
      bonds_.broken[k0 + k] = static_cast<std::uint8_t>(broken[row_start[j] + k]);
      if (!sp_.empty()) sp_[k0 + k] = plastic[row_start[j] + k];
      if (!lps_td_.empty()) lps_td_[k0 + k] = deviatoric[row_start[j] + k];
    }
    s0_[l] = s0[j];
    dissipated_[l] = dissipated[j];
    contact_energy_[l] = contact_energy[j];
    stiff_contact_[l] = stiffness[j];
    if (contacts_built) local_.x[l] = Vec3{{x_build[3 * j], x_build[3 * j + 1], x_build[3 * j + 2]}};
    if (has_gas_) {
      gas_x_[l] = gas_x[j];
      gas_g_[l] = gas_g[j];
      vented_[l] = static_cast<std::uint8_t>(vented[j]);
      vent_velocity_[l] = Vec3{{vent_velocity[3 * j], vent_velocity[3 * j + 1], vent_velocity[3 * j + 2]}};
    }
    if (renewed) {
      const double* r = &renewal[5 * j];
      renewal_.x[l] = Vec3{{r[0], r[1], r[2]}};
      renewal_.X[l] = r[3];
      renewal_.skip[l] = static_cast<std::uint8_t>(r[4]);
    }
  }
  if (renewed) {
    build_renewed_gas_family();
    gas_renewals_ = static_cast<long>(a.integer("pd.gas.renewals"));
  }
  // A ghost's copy of a bond is its own end's (broken flags and micro-plastic stretches are kept
  // equal; the state-based plasticity, whose ends differ, runs on one rank).
  for (Index l : local_.own)
    for (Index k = bonds_.offset[l]; k < bonds_.offset[l + 1]; ++k) {
      const Index q = bonds_.other[k];
      if (!local_.ghost[q]) continue;
      const Index kq = bonds_.offset[q] + mirror_[k];
      bonds_.broken[kq] = bonds_.broken[k];
      if (!sp_.empty()) sp_[kq] = sp_[k];
    }
  // The contact list as it was built: built again at the positions of that build (same pairs, same
  // order), then the ghosts take the restored positions.
  if (contacts_built) {
    halo_.update(comm_, local_, s0_);
    rebuild_contacts();
    contact_.builds = builds;
  }
  contact_.skin = skin;
  // Whether a point vented since that build (the list is then rebuilt at the next step, as it
  // would have been; checkpoints without this key rebuild at the first step).
  vented_since_build_ = !a.has("pd.contact.vented_since_build") || a.integer("pd.contact.vented_since_build") != 0;
  sync_local();
  x_prev_ = local_.x;
  time_ = a.real("pd.time");
  steps_ = static_cast<long>(a.integer("pd.steps"));
  a.get_into("pd.scalars", {&external_work_, &damping_, &next_fragment_time_});
  const auto& by_rank = a.ints("pd.counters_by_rank");
  const bool same_ranks = by_rank.size() == static_cast<std::size_t>(3 * comm_.size());
  const auto& cn = a.ints("pd.counters", 2);
  const std::size_t at = 3 * static_cast<std::size_t>(comm_.rank());
  vented_count_ = same_ranks ? static_cast<Index>(by_rank[at]) : comm_.rank() == 0 ? static_cast<Index>(cn[0]) : 0;
  gas_rate_limited_ =
      same_ranks ? static_cast<Index>(by_rank[at + 1]) : comm_.rank() == 0 ? static_cast<Index>(cn[1]) : 0;
  halo_.set_offered_bytes(same_ranks ? by_rank[at + 2] : 0);
  const auto width = static_cast<std::size_t>(a.integer("pd.fragment_row_width"));
  const auto& rows = a.reals("pd.fragment_rows");
  fragment_rows_.clear();
  for (std::size_t at = 0; width > 0 && at + width <= rows.size(); at += width)
    fragment_rows_.emplace_back(rows.begin() + static_cast<std::ptrdiff_t>(at),
                                rows.begin() + static_cast<std::ptrdiff_t>(at + width));
  loads_current_ = false;  // the loads at the restored positions are computed at the next step
}

}  // namespace ballista
