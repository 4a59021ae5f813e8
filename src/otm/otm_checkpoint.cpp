// Checkpoint and restart of the OTM solver (docs/restart.md). The supports are stored,
// not rebuilt: the LME solves are warm-started from the multipliers of the previous build, so a
// rebuild at restart would converge to the same functions only to within the solver tolerance.
// On several ranks the per-point state (supports, multipliers, stretch scales) is gathered to
// rank 0 in the points' order of the checkpoint (rank order), so the checkpoint is the one a
// serial run writes and restarts on any rank count: each rank's points are a contiguous run of
// that order (PointSet::load_state), and it takes their rows, sorted by id if they are not (the
// node sums' order). The nodes are every rank's alike.
#include <algorithm>
#include <cstring>

#include "core/error.hpp"
#include "otm/otm_solver.hpp"
#include "points/point_exchange.hpp"

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

/// Several ranks: every rank's support rows on rank 0, in rank order (the others get none).
otm::Supports gather_supports(const Communicator& comm, const otm::Supports& s) {
  std::vector<double> length, node, N, dN;
  for (Index p = 0; p + 1 < static_cast<Index>(s.offset.size()); ++p)
    length.push_back(static_cast<double>(s.offset[p + 1] - s.offset[p]));
  for (const std::int32_t a : s.node) node.push_back(a);
  N = s.N;
  for (const Vec3& g : s.dN) dN.insert(dN.end(), {g[0], g[1], g[2]});
  length = gather_values(comm, length);
  node = gather_values(comm, node);
  N = gather_values(comm, N);
  dN = gather_values(comm, dN);
  otm::Supports out;
  if (comm.rank() != 0) return out;
  out.offset.assign(1, 0);
  for (const double l : length) out.offset.push_back(out.offset.back() + static_cast<Index>(l));
  out.node.assign(node.begin(), node.end());
  out.N = std::move(N);
  for (std::size_t k = 0; k < out.node.size(); ++k) out.dN.push_back(Vec3{{dN[3 * k], dN[3 * k + 1], dN[3 * k + 2]}});
  return out;
}

/// Rows [first, first + n) of a checkpoint's supports (empty stays empty: no previous build).
/// Rows rows[0], rows[1], ... of `all` (a point's supports).
otm::Supports rows_of(const otm::Supports& all, const std::vector<Index>& rows) {
  if (all.offset.empty()) return all;
  otm::Supports s;
  s.offset.push_back(0);
  for (const Index p : rows) {
    const Index k0 = all.offset[p], k1 = all.offset[p + 1];
    s.node.insert(s.node.end(), all.node.begin() + k0, all.node.begin() + k1);
    s.N.insert(s.N.end(), all.N.begin() + k0, all.N.begin() + k1);
    s.dN.insert(s.dN.end(), all.dN.begin() + k0, all.dN.begin() + k1);
    s.offset.push_back(static_cast<Index>(s.node.size()));
  }
  return s;
}

template <class T>
std::vector<T> pick(const std::vector<T>& all, const std::vector<Index>& rows) {
  std::vector<T> out;
  if (all.empty()) return out;
  out.reserve(rows.size());
  for (const Index p : rows) out.push_back(all[static_cast<std::size_t>(p)]);
  return out;
}

/// Several ranks: every rank's records on rank 0, in rank order.
template <class T>
std::vector<T> gather_records(const Communicator& comm, const std::vector<T>& mine) {
  constexpr std::size_t k = sizeof(T) / sizeof(double);
  std::vector<double> flat(mine.size() * k);
  if (!mine.empty()) std::memcpy(flat.data(), mine.data(), flat.size() * sizeof(double));
  flat = gather_values(comm, flat);
  std::vector<T> out(flat.size() / k);
  if (!out.empty()) std::memcpy(static_cast<void*>(out.data()), flat.data(), flat.size() * sizeof(double));
  return out;
}

}  // namespace

void OtmSolver::save_state(StateArchive& a) const {
  pts_.save_state(a);  // collective: rank 0's archive holds every rank's points in rank order
  const bool ranks = comm_.distributed();
  // A rank whose points left the box this step has no previous supports: then none are kept.
  const bool previous = !comm_.any(prev_sup_.offset.empty());
  const otm::Supports cur = ranks ? gather_supports(comm_, sup_) : otm::Supports{};
  const otm::Supports prev = ranks && previous ? gather_supports(comm_, prev_sup_) : otm::Supports{};
  const std::vector<Vec3> lambda = ranks ? gather_records(comm_, lambda_) : std::vector<Vec3>{};
  const std::vector<double> scale = ranks ? gather_values(comm_, scale_) : std::vector<double>{};
  const std::vector<Mat3> Fr = ranks ? gather_records(comm_, Fr_) : std::vector<Mat3>{};
  if (comm_.rank() != 0) return;
  const SupportTotals& t = support_totals_;
  a.put_real("otm.time", time_);
  a.put_int("otm.steps", steps_);
  a.put("otm.scalars", std::vector<double>{damping_, dt_prev_, external_work_, damping_work_, wall_work_, wall_force_,
                                           remap_work_, momentum0_[0], momentum0_[1], momentum0_[2], t.mean,
                                           t.max_condition});
  a.put("otm.counters", std::vector<std::int64_t>{next_id_, static_cast<std::int64_t>(splits_),
                                                  static_cast<std::int64_t>(regenerations_), t.max_size,
                                                  t.max_iterations, static_cast<std::int64_t>(t.fallbacks),
                                                  static_cast<std::int64_t>(t.retries)});
  a.put_int("otm.light_node_steps", carried_node_steps_);
  if (contact_) a.put_real("otm.contact_work", contact_work_);
  a.put_records("otm.nodes.x", nodes_.x);
  a.put_records("otm.nodes.v", nodes_.v);
  a.put_records("otm.nodes.f", nodes_.f);
  a.put("otm.nodes.mass", nodes_.mass);
  a.put("otm.nodes.body", nodes_.body);
  put_supports(a, "otm.supports.", ranks ? cur : sup_);
  put_supports(a, "otm.previous_supports.", ranks ? prev : prev_sup_);
  a.put_records("otm.lambda", ranks ? lambda : lambda_);
  a.put("otm.scale", ranks ? scale : scale_);
  a.put_records("otm.Fr", ranks ? Fr : Fr_);
  a.put_integers("otm.interpolated", interpolated_);
}

void OtmSolver::load_state(const StateArchive& a) {
  pts_.load_state(a);
  // This rank's points are the checkpoint's rows [first, first + n).
  const Index n = points_.size();
  Index first = 0;
  if (comm_.distributed()) {
    std::vector<int> counts;
    const std::vector<std::int64_t> all = comm_.all_gather(std::vector<std::int64_t>{n}, counts);
    for (int r = 0; r < comm_.rank(); ++r) first += all[static_cast<std::size_t>(r)];
  }
  time_ = a.real("otm.time");
  steps_ = static_cast<long>(a.integer("otm.steps"));
  a.get_into("otm.scalars", {&damping_, &dt_prev_, &external_work_, &damping_work_, &wall_work_, &wall_force_,
                             &remap_work_, &momentum0_[0], &momentum0_[1], &momentum0_[2], &mean_support_,
                             &max_condition_});
  a.get_integers_into("otm.counters", next_id_, splits_, regenerations_, max_support_, max_iterations_, fallbacks_,
                      retries_);
  // Checkpoints written before light nodes were carried have none.
  carried_node_steps_ = a.has("otm.light_node_steps") ? a.integer("otm.light_node_steps") : 0;
  if (comm_.rank() != 0) fallbacks_ = retries_ = 0;  // totals: counted once, on rank 0
  if (contact_) contact_work_ = a.real("otm.contact_work");
  a.get_records("otm.nodes.x", nodes_.x);
  const std::size_t nn = nodes_.x.size();
  a.get_records("otm.nodes.v", nodes_.v, nn);
  a.get_records("otm.nodes.f", nodes_.f, nn);
  nodes_.mass = a.reals("otm.nodes.mass", nn);
  nodes_.body = a.ints("otm.nodes.body", nn);
  otm::Supports cur, prev;
  get_supports(a, "otm.supports.", cur);
  if (cur.size() < first + n)
    throw Error("the checkpoint holds the OTM supports of " + std::to_string(cur.size()) + " points, fewer than its " +
                std::to_string(first + n) + " points");
  get_supports(a, "otm.previous_supports.", prev);
  // This rank's rows, in id order: the serial run's point order, in which the node sums fold a
  // node's points (otm/node_sums.hpp). Its own rows on as many ranks are in that order already; a
  // share of a checkpoint written on another rank count after splits (each rank's children after
  // its own points) is sorted here.
  std::vector<Index> order(static_cast<std::size_t>(n));
  for (Index k = 0; k < n; ++k) order[k] = k;
  const auto* id = points_.ints(kId);
  if (!std::is_sorted(id, id + n)) {
    std::sort(order.begin(), order.end(), [&](Index x, Index y) { return id[x] < id[y]; });
    points_.permute(order);
    pts_.mark_reordered();
  }
  std::vector<Index> rows(order);
  for (Index& r : rows) r += first;
  sup_ = rows_of(cur, rows);
  // Right after a split the last step's supports lack the children's rows; the next build then
  // does not read them (otm::build_supports takes previous supports only for every point).
  prev_sup_ = prev.size() == cur.size() ? rows_of(prev, rows) : otm::Supports{};
  std::vector<Vec3> lambda;
  a.get_records("otm.lambda", lambda);
  lambda_ = pick(lambda, rows);
  scale_ = pick(a.reals("otm.scale"), rows);
  std::vector<Mat3> Fr;
  a.get_records("otm.Fr", Fr);
  Fr_ = pick(Fr, rows);
  a.get_integers("otm.interpolated", interpolated_);
  rebuild_influences();
  reduce_support_statistics();
}

}  // namespace ballista
