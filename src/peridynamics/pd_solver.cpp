#include "peridynamics/pd_solver.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/agreed_failure.hpp"
#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "geometry/seeding.hpp"
#include "geometry/shape.hpp"
#include "peridynamics/bond_pass.hpp"
#include "peridynamics/fragments.hpp"
#include "peridynamics/pd_fields.hpp"
#include "peridynamics/pd_params.hpp"
#include "points/rcb_partition.hpp"
#include "points/solver_registry.hpp"
#include "scenario/material_model.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Storage per bond end: the family (BondFamily::kBytesPerBond) plus the half-bond pass's mirror
/// position and inverse length (the micro-plastic stretch adds 8 B when present).
constexpr double kSolverBytesPerBond = pd::BondFamily::kBytesPerBond + sizeof(std::int32_t) + sizeof(double);

/// Storage per bond end with the deck's options: a plastic stretch or extension per end, and for
/// the state-based plasticity the bond's length and deviatoric force state of the last evaluation.
double solver_bytes_per_bond(const PdParams& p) {
  const double plastic = p.yield_stress ? sizeof(double) : 0.0;
  return kSolverBytesPerBond + plastic + (p.lps ? 2.0 * plastic : 0.0);
}

}  // namespace

PdSolver::PdSolver(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, Communicator comm)
    : scenario_(sc),
      params_(read_pd_params(sc)),
      comm_(comm),
      // Every body on the lattice of spacing grid.cell_size (one point per cell); each point holds
      // its family's bond ends (m = 3 in 3D: 122 of solver_bytes_per_bond).
      pts_(sc, std::move(materials),
           SeedLattice{sc.grid, 1, params_.full_family_size(sc) * solver_bytes_per_bond(params_)}, 0.0,
           fmt::format("families of {:g} bond ends per point, set by peridynamics.m or horizon",
                       params_.full_family_size(sc)),
           comm),
      points_(pts_.store()) {
  read_settings(sc);
  nmat_ = static_cast<int>(pts_.materials().size());
  classify_materials(sc);
  read_body_scales(sc);
  set_bond_constants(sc);

  // Fields of this solver: damage (output) and the acceleration of the last force evaluation.
  points_.add_real("damage", 1, "1");
  points_.add_real("pd_accel", 3, "m/s^2", false);
  const auto build_start = std::chrono::steady_clock::now();
  build_local_points();
  const Index n = points_.size();  // own points
  const Index nl = local_.size(), nb = local_.bond_local;
  gas_.assign(static_cast<size_t>(n), 0);
  {
    const auto* mt = points_.ints("material");
    for (Index p = 0; p < n; ++p) gas_[p] = gas_material_[mt[p]];
  }
  // Every rank takes part in the gas's exchanges and reductions if any rank holds gas.
  has_gas_ = comm_.any(std::find(gas_.begin(), gas_.end(), 1) != gas_.end());
  if (has_gas_) build_gas();
  // The renewed family needs every neighbour within the current horizon, which another rank's
  // points may be: one rank only so far (docs/parallel.md).
  if (params_.gas_refamily_steps > 0 && has_gas_ && comm_.distributed())
    pd_section_error(sc, "gas_refamily_steps",
                     "renewing the gas family runs on one MPI rank only so far (" + std::to_string(comm_.size()) +
                         " ranks were started; set it to 0 or run on one rank)");
  init_critical_stretch();
  // Per bond end: the micro-plastic bond's stretch, or the LPS plastic extension of that end.
  if (std::isfinite(yield_stretch_) || (params_.lps && params_.yield_stress)) sp_.assign(bonds_.other.size(), 0.0);
  if (params_.lps && params_.yield_stress && comm_.distributed())
    pd_section_error(sc, "yield_stress",
                     "the state-based plasticity runs on one MPI rank so far (a bond's force needs the plastic "
                     "extension at its other end, which another rank's return computes; " +
                         std::to_string(comm_.size()) + " ranks were started)");
  dissipated_.assign(static_cast<size_t>(nl), 0.0);
  contact_energy_.assign(static_cast<size_t>(nl), 0.0);
  contact_.skin = params_.contact_skin * dx_;
  build_bond_tables();
  if (params_.lps) build_lps_weighted_volumes();
  bond_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
  stiff_bond_.assign(static_cast<size_t>(nb), 0.0);
  stiff_contact_.assign(static_cast<size_t>(nl), 0.0);
  x_prev_ = local_.x;
  apply_surface_correction();
  set_bond_stiffness();
  cut_pre_cracks(sc);
  sync_local();
  x_prev_ = local_.x;
  if (params_.contact) rebuild_contacts();
  compute_forces();
}

void PdSolver::read_settings(const Scenario& sc) {
  // Explosives are a peridynamic gas (gas_pass.hpp): a pressure from the material library, no
  // bond stiffness. The products' pressure of a plane-stress plate has no meaning.
  if (const MaterialSpec* m = first_material_of_model(sc, "explosive"); m && sc.simulation.plane_stress)
    throw DeckError(m->mark.file, m->mark.line, m->mark.column, m->mark.key_path + ".model",
                    "an explosive (a peridynamic gas) needs dimension 3d or plane_strain, not plane_stress");
  dx_ = sc.grid.cell_size;
  delta_ = params_.horizon;
  next_fragment_time_ = params_.fragment_interval > 0.0 ? params_.fragment_interval : kInf;
  damping_ = sc.simulation.damping;
  dim_ = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  thickness_ = params_.thickness;
  if (pts_.pending() > 0)
    pd_section_error(sc, "", "bodies with a later activation (activation_time, activation_stage, rods, jets) are not "
                          "supported by the peridynamics solver yet: their bonds would have to be built on arrival");
  if (sc.simulation.on_particle_exit != "stop")
    pd_section_error(sc, "", "simulation.on_particle_exit: delete is not supported by the peridynamics solver yet");
}

void PdSolver::build_local_points() {
  // Every rank seeded every body (PointSet): the owner of each point by RCB of the reference
  // positions, each rank computing the cuts for its contiguous share, the owners then known to all.
  const Index n_all = points_.size();
  const auto* id = points_.ints("id");
  const auto* x0 = points_.view<Vec3>("x0");
  for (Index p = 1; p < n_all; ++p)
    if (id[p] <= id[p - 1]) throw Error("peridynamics: the seeded points are not in increasing id order");
  global_points_ = n_all;
  const int me = comm_.rank();
  std::vector<int> owner(static_cast<size_t>(n_all), 0);
  if (comm_.distributed()) {
    const Index lo = n_all * me / comm_.size(), hi = n_all * (me + 1) / comm_.size();
    RcbPartition rcb(comm_, dim_);
    const std::vector<int> dest = rcb.partition(x0 + lo, id + lo, hi - lo);
    std::vector<int> counts;
    const std::vector<std::int64_t> all = comm_.all_gather(std::vector<std::int64_t>(dest.begin(), dest.end()), counts);
    if (static_cast<Index>(all.size()) != n_all) throw Error("peridynamics: the partition lost points");
    for (Index p = 0; p < n_all; ++p) owner[p] = static_cast<int>(all[p]);
  }
  // Candidates: own points and every point within the horizon of this rank's own points' box.
  constexpr double kBig = std::numeric_limits<double>::infinity();
  Vec3 lo{{kBig, kBig, kBig}}, hi{{-kBig, -kBig, -kBig}};
  for (Index p = 0; p < n_all; ++p)
    if (owner[p] == me)
      for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], x0[p][c]), hi[c] = std::max(hi[c], x0[p][c]);
  const double grow = delta_ * max_scale_ * (1.0 + 1e-6);  // a coarse gas lattice reaches farther
  std::vector<Index> cand;
  for (Index p = 0; p < n_all; ++p) {
    bool near = owner[p] == me;
    if (!near) {
      near = true;
      for (int c = 0; c < dim_; ++c) near = near && x0[p][c] >= lo[c] - grow && x0[p][c] <= hi[c] + grow;
    }
    if (near) cand.push_back(p);
  }
  const Index nc = static_cast<Index>(cand.size());
  std::vector<Vec3> cx0(static_cast<size_t>(nc));
  std::vector<std::int64_t> cbody(static_cast<size_t>(nc));
  std::vector<std::uint8_t> cgas(static_cast<size_t>(nc));
  const auto* body = points_.ints("body");
  const auto* mat = points_.ints("material");
  for (Index c = 0; c < nc; ++c) {
    cx0[c] = x0[cand[c]];
    cbody[c] = body[cand[c]];
    cgas[c] = gas_material_[mat[cand[c]]];
  }
  const double partial_dx = params_.partial_volumes ? dx_ : 0.0;  // 0: no partial-volume correction
  bonds_ = pd::build_bond_family(cx0.data(), nc, delta_, partial_dx, dim_, cbody.data(), cgas.data());
  // Detonation products: the gas family (every pair within the horizon with a gas end, gas_pass.hpp).
  const bool any_gas = std::find(gas_material_.begin(), gas_material_.end(), 1) != gas_material_.end();
  if (any_gas) {
    std::vector<double> cscale(static_cast<size_t>(nc), 1.0);
    for (Index c = 0; c < nc; ++c) cscale[c] = cgas[c] ? body_scale_[cbody[c]] : 1.0;
    gas_bonds_ = pd::build_gas_family(cx0.data(), nc, delta_, partial_dx, dim_, cgas.data(),
                                      max_scale_ > 1.0 ? cscale.data() : nullptr);
  }
  std::vector<char> keep(static_cast<size_t>(nc), 1);
  if (comm_.distributed()) {
    // Ghosts: the candidates bonded (or gas-bonded) to an own point; their rows keep only those bonds.
    std::vector<char> owned(static_cast<size_t>(nc), 0);
    for (Index c = 0; c < nc; ++c) owned[c] = owner[cand[c]] == me;
    auto bonded_to_own = [&](const pd::BondFamily& f, Index c) {
      for (Index k = f.offset[c]; k < f.offset[c + 1]; ++k)
        if (owned[f.other[k]]) return true;
      return false;
    };
    for (Index c = 0; c < nc; ++c)
      keep[c] = owned[c] || bonded_to_own(bonds_, c) || (any_gas && bonded_to_own(gas_bonds_, c));
    bonds_ = pd::restrict_family(bonds_, keep, owned);
    if (any_gas) gas_bonds_ = pd::restrict_family(gas_bonds_, keep, owned);
  }
  const auto* x = points_.view<Vec3>("x");
  const auto* vol0 = points_.real(kReferenceVolume);
  local_ = pd::LocalPoints{};
  std::vector<int> ghost_owner;
  for (Index c = 0; c < nc; ++c) {
    if (!keep[c]) continue;
    const Index p = cand[c];
    local_.push(id[p], body[p], mat[p], x0[p], x[p], vol0[p], owner[p] == me);
    ghost_owner.push_back(owner[p]);
  }
  local_.bond_local = local_.size();
  halo_.plan_bond_ghosts(comm_, local_, ghost_owner);
  if (comm_.distributed()) {
    std::vector<char> mine(static_cast<size_t>(n_all), 0);
    for (Index p = 0; p < n_all; ++p) mine[p] = owner[p] == me;
    pts_.keep(mine);  // the store holds the own points, in id order
  }
}

void PdSolver::sync_local() {
  const Index n = points_.size(), nl = local_.size();
  const auto* x = points_.view<Vec3>("x");
  const auto& own = local_.own;
  for_each(0, n, [&](Index i) { local_.x[own[i]] = x[i]; });
  if (!comm_.distributed()) return;
  for (Index l = 0; l < nl; ++l)
    if (local_.ghost[l]) x_prev_[l] = local_.x[l];
  halo_.update(comm_, local_, s0_);
}

bool PdSolver::contacts_stale() const {
  // Vented points take no part in contact. On one rank the force loop skips their pairs (every
  // point's vented flag is current), so venting needs no rebuild; on several ranks a ghost's flag
  // is its owner's, so a point vented since the build leaves the list at once.
  if (!comm_.distributed()) {
    const double ms = contact_.solid_moved(local_.x.data(), local_.size(), skip_vented(), skip_gas());
    if (!contact_.stale(local_.x.data(), local_.size(), ms, skip_vented(), skip_gas())) return false;
    // Every point has moved far, but maybe together (an expanding case): the test on relative
    // motion, which costs a binning, decides (contact_list.hpp). Either test passing keeps every
    // pair within reach listed, and the forces do not depend on the list beyond that.
    return contact_.stale_relative(local_.x.data(), local_.size(), dim_, skip_vented(), skip_gas());
  }
  // Own points only (each rank checks its own), vented gas aside; the solids' largest motion over
  // every rank (a gas point's partners may be another rank's).
  const std::uint8_t* gas = has_gas_ ? gas_local_.data() : nullptr;
  const std::uint8_t* skip = local_.ghost.data();
  std::vector<std::uint8_t> mask;
  if (has_gas_) {
    mask.assign(local_.ghost.begin(), local_.ghost.end());
    for (Index l = 0; l < local_.size(); ++l) mask[l] |= vented_[l];
    skip = mask.data();
  }
  const double ms = comm_.max(contact_.solid_moved(local_.x.data(), local_.size(), skip, gas));
  return comm_.any(vented_since_build_ || contact_.stale(local_.x.data(), local_.size(), ms, skip, gas));
}

void PdSolver::resize_local_arrays() {
  const auto nl = static_cast<size_t>(local_.size());
  x_prev_.resize(nl), s0_.resize(nl), dissipated_.resize(nl), contact_energy_.resize(nl), stiff_contact_.resize(nl);
  if (!has_gas_) return;
  // Contact ghosts: gas or not by their material; never vented (only unvented points are offered).
  gas_local_.resize(nl);
  gas_scale_.resize(nl);
  vented_.resize(nl);
  for (Index l = local_.bond_local; l < local_.size(); ++l) {
    gas_local_[l] = gas_material_[local_.material[l]];
    gas_scale_[l] = gas_local_[l] ? body_scale_[local_.body[l]] : 1.0;
    vented_[l] = 0;
  }
}

void PdSolver::rebuild_contacts() {
  const double cutoff = 0.675 * dx_ * (1.0 + max_scale_) + contact_.skin;  // the farthest pair's (contact_list.hpp)
  vented_since_build_ = false;
  if (!comm_.distributed()) {
    // One rank holds every solid: gas far from them may move by its clearance.
    pd::build_contact_list(contact_, local_.x.data(), local_.x0.data(), local_.body.data(), local_.size(), delta_, dx_,
                           contact_.skin, dim_, skip_vented(), skip_gas(), nullptr, true,
                           max_scale_ > 1.0 ? gas_scale_.data() : nullptr);
    return;
  }
  if (has_gas_) {
    // The bond ghosts' vented flags from their owners (vented points take no part in contact).
    std::vector<double> flag(vented_.begin(), vented_.end());
    halo_.update_bond_values(comm_, local_, flag);
    for (Index l = 0; l < local_.bond_local; ++l) vented_[l] = flag[l] != 0.0;
  }
  halo_.gather_contact_ghosts(comm_, local_, cutoff, dim_, skip_vented());
  resize_local_arrays();
  const Index nl = local_.size();
  pd::build_contact_list(contact_, local_.x.data(), local_.x0.data(), local_.body.data(), nl, delta_, dx_,
                         contact_.skin, dim_, skip_vented(), has_gas_ ? gas_local_.data() : nullptr, local_.id.data(),
                         false, max_scale_ > 1.0 && has_gas_ ? gas_scale_.data() : nullptr);
  // Keep the contact ghosts some own point's row names; only own rows stay (ghost rows are their
  // owners' business).
  std::vector<char> needed(static_cast<size_t>(nl), 0);
  for (Index l : local_.own)
    for (Index k = contact_.offset[l]; k < contact_.offset[l + 1]; ++k) needed[contact_.other[k]] = 1;
  const std::vector<Index> renumber = halo_.keep_contact_ghosts(comm_, local_, needed);
  const Index m = local_.size();
  pd::ContactList kept;
  kept.skin = contact_.skin;
  kept.max_reach = contact_.max_reach;
  kept.builds = contact_.builds;
  kept.offset.assign(static_cast<size_t>(m) + 1, 0);
  kept.x_build.resize(static_cast<size_t>(m));
  if (!contact_.allowance.empty()) kept.allowance.resize(static_cast<size_t>(m));
  for (Index l = 0; l < nl; ++l)
    if (renumber[l] >= 0) {
      kept.x_build[renumber[l]] = contact_.x_build[l];
      if (!kept.allowance.empty()) kept.allowance[renumber[l]] = contact_.allowance[l];
    }
  for (Index l = 0; l < local_.bond_local; ++l) {
    if (!local_.ghost[l])
      for (Index k = contact_.offset[l]; k < contact_.offset[l + 1]; ++k) {
        kept.other.push_back(static_cast<std::int32_t>(renumber[contact_.other[k]]));
        kept.reach.push_back(contact_.reach[k]);
      }
    kept.offset[l + 1] = static_cast<Index>(kept.other.size());
  }
  for (Index l = local_.bond_local; l < m; ++l) kept.offset[l + 1] = kept.offset[l];
  contact_ = std::move(kept);
  resize_local_arrays();
}

void PdSolver::refresh() {
  loads_current_ = false;
  sync_local();
  x_prev_ = local_.x;
  compute_forces();
}

Index PdSolver::cut_bonds(const std::function<bool(Index, Index)>& cut) {
  // Every local row (a ghost's copies too), counted at own points (collective).
  std::int64_t count = 0;
  for (Index p = 0; p < bonds_.points(); ++p)
    for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k) {
      const Index q = bonds_.other[k];
      if (bonds_.broken[k] || !(cut(p, q) || cut(q, p))) continue;
      bonds_.broken[k] = 1;
      count += local_.ghost[p] ? 0 : 1;
    }
  return static_cast<Index>(comm_.sum(count) / 2);  // each bond is stored at both of its ends (the test is symmetric)
}

Index PdSolver::break_bonds(const std::function<bool(const Vec3&, const Vec3&)>& cut) {
  const auto* x0 = local_.x0.data();
  const Index count = cut_bonds([&](Index p, Index q) { return cut(x0[p], x0[q]); });
  compute_forces();
  return count;
}

void PdSolver::begin_stage(int stage, double damping) {
  pts_.begin_stage(stage, time_);
  damping_ = damping;
}

double PdSolver::stable_dt() {
  // Silling & Askari 2005 eq. 17 with the active contact springs counted like bonds (stiffness c_s V_q
  // each): a contact is as stiff as several bonds, and the step must stay stable while it acts.
  const Index n = points_.size();
  const auto* vol0 = points_.real(kReferenceVolume);
  const auto* mass = points_.real(kMass);
  const Index* own = local_.own.data();
  double dt = kInf;
#pragma omp parallel for schedule(static) reduction(min : dt) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) {
    const Index l = own[p];
    const double sum = stiff_bond_[l] + stiff_contact_[l];
    if (sum > 0.0) dt = std::min(dt, std::sqrt(2.0 * mass[p] / vol0[p] / sum));
  }
  if (has_gas_) dt = std::min(dt, gas_stable_dt());
  dt = comm_.min(params_.dt_safety * dt);
  if (!std::isfinite(dt)) dt = scenario_.simulation.end_time;  // no bonds at all: free flight
  if (scenario_.simulation.max_dt > 0.0) dt = std::min(dt, scenario_.simulation.max_dt);
  return dt;
}

void PdSolver::compute_forces() {
  // Over the local points (own and ghosts, local_.x current: sync_local); results to own points.
  const Index n = points_.size(), nl = local_.size();
  const auto* x = local_.x.data();
  const auto* vol0 = local_.vol0.data();
  const auto* mass = points_.real(kMass);
  const auto* mat = local_.material.data();
  const Index* own = local_.own.data();
  auto* acc = points_.view<Vec3>("pd_accel");
  auto* damage = points_.real(pd::kBondDamage);
  auto* eint = points_.real(kInternalEnergy);
  auto* wdis = points_.real(kPlasticWork);
  const double* s0 = s0_.data();
  const double* len0 = bonds_.length0.data();
  const float* beta = bonds_.volume_factor.data();
  const std::int32_t* other = bonds_.other.data();
  const std::int32_t* mirror = mirror_.data();
  std::uint8_t* broken = bonds_.broken.data();
  const double alpha = params_.stretch_alpha;
  const bool plastic = !sp_.empty();
  double* sp = sp_.data();
  const double sy = yield_stretch_;
  const Vec3* xprev = x_prev_.data();  // positions at the step's start (= x outside a step)
  // Short-range contact (contact_list.hpp): c_s = 15 c / delta per unit volume squared and unit
  // overlap (Silling & Askari 2005; LAMMPS pair_peri_pmb), reach d = min(0.9 |xi|, 1.35 dx).
  const bool contact = params_.contact;
  const bool bonded_contact = contact && params_.contact_all_pairs;
  const double cs_over_c = 15.0 / delta_, range = 1.35 * dx_;
  // Per-point sums of this evaluation (each bond adds to both of its ends).
  Acc& A = acc_;
  A.resize(nl);
  for_each(0, nl, [&](Index p) { A.clear(p); });

  if (nl == 0) return;
  if (params_.lps) {
    lps_pass();
  } else {
    pd::BondPassArgs args{x[0].v,
                          vol0,
                          mat,
                          c_.data(),
                          nmat_,
                          s0,
                          len0,
                          inv_len0_.data(),
                          beta,
                          other,
                          mirror,
                          broken,
                          bonds_.offset.data(),
                          upper_.data(),
                          plastic ? sp : nullptr,
                          sy,
                          alpha,
                          contact,
                          bonded_contact,
                          cs_over_c,
                          range,
                          xprev[0].v,
                          A.f[0].v,
                          A.energy.data(),
                          A.dis.data(),
                          A.vol_broken.data(),
                          A.smx.data(),
                          A.e_contact.data(),
                          A.k_contact.data(),
                          surface_factor_.empty() ? nullptr : surface_factor_.data(),
                          params_.lammps_break};
    const Index nblock = static_cast<Index>(block_start_.size()) - 1;
    for (int phase = 0; phase < 2; ++phase) {
      const Index nphase = (nblock - phase + 1) / 2;
#pragma omp parallel for schedule(dynamic, 1) if (nphase > 1 && n > kParallelThreshold)
      for (Index j = 0; j < nphase; ++j) {
        const Index b = 2 * j + phase;
        pd::bond_pass(args, block_start_[b], block_start_[b + 1]);
      }
    }
  }

  // Never-bonded neighbours (other bodies, or beyond the horizon): both rows hold the pair, so each
  // point sums its own row. Then each point's results.
  std::vector<double>& s0_next = s0_next_;
  s0_next.resize(static_cast<size_t>(nl));
  const bool gas_on = has_gas_;
  const pd::GasPassArgs gas_args = gas_pass_args();
  const std::uint8_t* vent = has_gas_ ? vented_.data() : nullptr;
  for_each_uneven(0, n, [&](Index i) {  // gas points carry their gas pairs too
    const Index p = own[i];  // the same on one rank (gas only there)
    Vec3 f = A.f[p];
    double e_contact = A.e_contact[p], k_contact = A.k_contact[p];
    if (contact && !(vent && vent[p]))
      for (Index k = contact_.offset[p]; k < contact_.offset[p + 1]; ++k) {
        const Index q = contact_.other[k];
        if (vent && vent[q]) continue;  // vented since the build (contacts_stale)
        const Vec3 y = x[q] - x[p];
        const double r = norm(y), d = contact_.reach[k];
        if (r >= d) continue;
        const double cs = cs_over_c * c_contact_[mat[p] * nmat_ + mat[q]], o = d - r;
        k_contact += cs * vol0[q];
        if (r > 0.0) f += (-cs * o * vol0[q] * vol0[p] / r) * y;
        e_contact += 0.25 * cs * o * o * vol0[q] * vol0[p];
      }
    if (gas_on) f += pd::gas_force(gas_args, p);
    acc[i] = (1.0 / mass[i]) * f;
    damage[i] = std::min(1.0, A.vol_broken[p] / vol_all_[p]);  // round-off of the two sums: never above 1
    dissipated_[p] += A.dis[p];
    contact_energy_[p] = e_contact;
    stiff_contact_[p] = k_contact;
    if (!gas_on || !gas_[i]) {  // a gas point's energy is the material's stress-power integral
      eint[i] = A.energy[p] + dissipated_[p] + e_contact;
      wdis[i] = dissipated_[p];
    }
    const double s00 = s00_point_[p];
    s0_next[p] = alpha > 0.0 && std::isfinite(A.smx[p]) ? s00 + A.smx[p] : s00;
  });
  s0_.swap(s0_next);
}

void PdSolver::step(double dt) {
  // A failure on one rank (a point not finite or out of the box, found after the step's last
  // collective) stops every rank with the lowest failing rank's diagnostic (core/agreed_failure.hpp).
  run_agreed(comm_, [&] { advance(dt); });
}

void PdSolver::advance(double dt) {
  // Velocity Verlet (Silling & Askari 2005 §4 use the explicit central difference; Verlet is the
  // same scheme with synchronised velocities): v_{n+1/2} = v_n + dt/2 a_n, x_{n+1} = x_n + dt
  // v_{n+1/2}, a_{n+1} from the bonds at x_{n+1}, v_{n+1} = v_{n+1/2} + dt/2 a_{n+1}. External
  // forces enter a with the loads of the step's start and end.
  const Index n = points_.size();
  auto* x = points_.view<Vec3>("x");
  auto* v = points_.view<Vec3>("v");
  const auto* mass = points_.real(kMass);
  // The loads at (x_n, t_n) are the previous step's end-of-step loads (same positions, same time):
  // computed again only after the positions were changed from outside (refresh) or at the start.
  if (!loads_current_) loads_.compute(scenario_, points_, time_);
  f0_ = loads_.total();
  const std::vector<Vec3>& f0 = f0_;
  const bool has_ext = !f0.empty();
  const double c = damping_;
  std::vector<Vec3>& v_half = v_half_;
  v_half.resize(static_cast<size_t>(n));
  Vec3* x_prev = x_prev_.data();
  const Index* own = local_.own.data();
  {
    const auto* acc = points_.view<Vec3>("pd_accel");
    const std::uint8_t* vented = vented_.empty() ? nullptr : vented_.data();
    for_each(0, n, [&](Index p) {
      x_prev[own[p]] = x[p];
      if (vented && vented[own[p]]) {  // vented gas flies on, force-free and out of the balance
        v_half[p] = Vec3{};
        x[p] += dt * vent_velocity_[own[p]];
        return;
      }
      Vec3 a = acc[p] - c * v[p];
      if (has_ext) a += (1.0 / mass[p]) * f0[p];
      v[p] += (0.5 * dt) * a;
      v_half[p] = v[p];
      x[p] += dt * v[p];
    });
  }
  sync_local();
  // Several ranks: a failure of the products' update (a non-finite pressure) is thrown only after
  // the step's last exchange, so that the other ranks are not left waiting in it.
  std::exception_ptr gas_failure;
  if (has_gas_) {
    try {
      update_gas(dt);
    } catch (const std::exception&) {
      if (!comm_.distributed()) throw;
      gas_failure = std::current_exception();
    }
    halo_.update_bond_values(comm_, local_, gas_g_);  // the ghosts' push G for the pair forces
  }
  if (params_.contact && contacts_stale()) rebuild_contacts();
  compute_forces();
  time_ += dt;
  ++steps_;
  if (time_ >= next_fragment_time_ * (1.0 - 1e-12)) {
    auto rows = fragment_rows(fragments());
    fragment_rows_.insert(fragment_rows_.end(), rows.begin(), rows.end());
    while (next_fragment_time_ <= time_ * (1.0 + 1e-12)) next_fragment_time_ += params_.fragment_interval;
  }
  loads_.compute(scenario_, points_, time_);
  loads_current_ = true;
  const std::vector<Vec3>& f1 = loads_.total();
  const auto* acc = points_.view<Vec3>("pd_accel");
  // Damping with the half-step velocity (explicit), as in the first half. The same pass finds the
  // first point whose state is not finite or that left the box (the domain of the points).
  const GridSpec& g = scenario_.grid;
  std::atomic<Index> bad{n};
  std::atomic<bool> left{false};
  const std::uint8_t* vented = vented_.empty() ? nullptr : vented_.data();
  for_each(0, n, [&](Index p) {
    if (vented && vented[own[p]]) return;
    Vec3 a = acc[p] - c * v[p];
    if (has_ext) a += (1.0 / mass[p]) * f1[p];
    v[p] += (0.5 * dt) * a;
    bool ok = all_finite(x[p]) && all_finite(v[p]);
    const bool inside = g.contains(x[p]);
    if (ok && !inside && vented && gas_[p]) {  // gas leaving the box is vented below, not a failure (a solid is)
      left = true;
      return;
    }
    if (!(ok && inside)) {
      Index cur = bad.load();
      while (p < cur && !bad.compare_exchange_weak(cur, p)) {
      }
    }
  });
  // Work of the external and damping forces over the step: force (trapezoidal in time) times the
  // displacement dt v_{n+1/2}, exact for a constant force.
  if (has_ext || c > 0.0) {
    double w[1];
    deterministic_sum<1>(0, n, [&](Index p, double* o) {
      if (has_ext) o[0] += dot(0.5 * (f0[p] + f1[p]), v_half[p]);
      o[0] -= c * mass[p] * dot(v_half[p], v_half[p]);
    }, w);
    external_work_ += dt * comm_.sum(w[0]);
  }
  if (gas_failure) std::rethrow_exception(gas_failure);
  if (left) vent_escaped_gas();
  // A non-finite position or velocity, or a point leaving the grid box, stops the run.
  if (const Index p = bad.load(); p < n) {
    if (!all_finite(x[p]) || !all_finite(v[p])) pts_.fail(p, "has a non-finite position or velocity", steps_, time_);
    pts_.fail(p, "left the grid box (the peridynamic domain)", steps_, time_);
  }
}

EnergyTotals PdSolver::energies() const {
  EnergyTotals e = pts_.energies(thickness_, external_work_);
  if (has_gas_) {
    // A gas point's internal_energy is the products' stress-power integral (the material's), so
    // its half of the contact springs it is pressed into (kept in internal_energy for solids)
    // joins the internal energy here.
    double s[1];
    deterministic_sum<1>(0, points_.size(), [&](Index p, double* o) {
      if (gas_[p]) o[0] += contact_energy_[local_.own[p]];
    }, s);
    e.internal += thickness_ * comm_.sum(s[0]);
  }
  return e;
}

Index PdSolver::broken_bonds() const {
  std::int64_t k = 0;
  for (Index l : local_.own)
    for (Index b = bonds_.offset[l]; b < bonds_.offset[l + 1]; ++b) k += bonds_.broken[b];
  return static_cast<Index>(comm_.sum(k) / 2);  // each bond is stored at both of its ends
}

std::vector<std::pair<std::string, double>> PdSolver::result_values() const {
  // Collective: the fragments are found on rank 0 (empty elsewhere), kept for result_tables().
  const std::vector<pd::Fragment> frags = fragments();
  final_rows_ = fragment_rows(frags);
  final_rows_time_ = time_;
  double total = 0.0, dmax = 0.0;
  for (const auto& f : frags) total += f.mass;
  const auto* damage = points_.real(pd::kBondDamage);
  for (Index p = 0; p < points_.size(); ++p) dmax = std::max(dmax, damage[p]);
  dmax = comm_.max(dmax);
  const double broken = static_cast<double>(broken_bonds());
  std::int64_t gas_bonds = 0;  // each counted at both ends, at own points
  if (has_gas_)
    for (Index l : local_.own) gas_bonds += gas_bonds_.offset[l + 1] - gas_bonds_.offset[l];
  gas_bonds = comm_.sum(gas_bonds);
  std::int64_t lone = 0;  // gas points whose renewed family is empty (they keep their X: pd_gas.cpp)
  if (has_gas_)
    for (Index p = 0; p < points_.size(); ++p) {
      const Index l = local_.own[p];
      lone += gas_[p] && !vented_[l] && !(gas_volume_[l] > 0.0);
    }
  lone = comm_.sum(lone);
  std::vector<std::pair<std::string, double>> out{{"broken_bonds", broken},
          {"fragment_count", static_cast<double>(frags.size())},
          {"largest_fragment_mass", frags.empty() ? 0.0 : thickness_ * frags.front().mass},
          {"mean_fragment_mass", frags.empty() ? 0.0 : thickness_ * total / static_cast<double>(frags.size())},
          {"max_damage", dmax},
          // Cost figures (docs/performance.md): the bond families with their solver arrays, the
          // contact list rebuilds, and the storage per bond end.
          {"contact_list_builds", static_cast<double>(contact_.builds)},
          {"bytes_per_bond_end", solver_bytes_per_bond(params_)},
          {"gas_bonds", static_cast<double>(gas_bonds) / 2.0},
          {"vented_gas_points", static_cast<double>(comm_.sum(static_cast<std::int64_t>(vented_count_)))},
          {"gas_rate_limited_steps", static_cast<double>(comm_.sum(static_cast<std::int64_t>(gas_rate_limited_)))},
          {"gas_family_renewals", static_cast<double>(gas_renewals_)},
          {"lone_gas_points", static_cast<double>(lone)}};
  if (comm_.distributed()) {
    // Several ranks: how the points are shared, and what rank 0 sends its neighbours per step
    // (its own points' ghost copies), one message per neighbouring rank.
    const double n = static_cast<double>(points_.size());
    const double fewest = comm_.min(n), most = comm_.max(n);  // collective: every rank reports
    out.insert(out.end(), {{"ranks", static_cast<double>(comm_.size())},
                           {"fewest_particles_on_a_rank", fewest},
                           {"most_particles_on_a_rank", most},
                           {"halo_bytes_per_step_rank0", static_cast<double>(halo_.bytes_per_update())},
                           {"halo_messages_per_step_rank0", static_cast<double>(halo_.peers().size())},
                           {"contact_ghost_offer_bytes_per_build_rank0",
                            static_cast<double>(halo_.offered_bytes()) / std::max<double>(1.0, contact_.builds)}});
  }
  return out;
}

std::vector<pd::Fragment> PdSolver::fragments() const {
  const double threshold = params_.fragment_damage_threshold;
  if (!comm_.distributed()) return pd::find_fragments(bonds_, points_, threshold, skip_gas());
  return pd::find_fragments_gathered(comm_, bonds_, local_.own, local_.id.data(), points_, threshold, gas_material_);
}

std::vector<std::vector<double>> PdSolver::fragment_rows(const std::vector<pd::Fragment>& frags) const {
  std::vector<std::vector<double>> rows;
  for (size_t k = 0; k < frags.size(); ++k) {
    const pd::Fragment& f = frags[k];
    // 2D: masses and energies of the plate of the given thickness.
    rows.push_back({time_, static_cast<double>(k), static_cast<double>(f.points), thickness_ * f.mass, f.center[0],
                    f.center[1], f.center[2], f.velocity[0], f.velocity[1], f.velocity[2], norm(f.velocity),
                    thickness_ * f.kinetic_energy});
  }
  return rows;
}

std::string PdSolver::derived_constants() const {
  std::string s = "# Derived by the peridynamics solver (not read back):\n";
  s += fmt::format("#   lattice_spacing: {:.10g}   # m (grid.cell_size)\n#   horizon: {:.10g}   # m\n", dx_, delta_);
  if (!sp_.empty() && !params_.lps)
    s += fmt::format("#   yield_stretch: {:.10g}   # micro-plastic bonds\n", yield_stretch_);
  const auto& mats = pts_.materials();
  if (params_.lps) {
    // The micromodulus below is the equivalent PMB bond's (stable step, contact springs: lps_constants.hpp).
    for (int a = 0; a < nmat_; ++a)
      if (!gas_material_[a])
        s += fmt::format("#   lps {}: {{bulk_modulus: {:.10g}, shear_modulus: {:.10g}}}   # Pa\n", mats[a]->name(),
                         lps_bulk_[a], lps_shear_[a]);
  }
  for (int a = 0; a < nmat_; ++a)
    for (int b = a; b < nmat_; ++b)
      s += fmt::format("#   bond {}-{}: {{micromodulus: {:.10g}, critical_stretch: {:.10g}}}   # N/m^6, 1\n",
                       mats[a]->name(), mats[b]->name(), c_[a * nmat_ + b], s00_[a * nmat_ + b]);
  return s;
}

std::vector<std::string> PdSolver::history_columns() const {
  std::vector<std::string> c = PointLoads::history_columns(scenario_);
  c.push_back("broken_bonds");
  c.push_back("mean_damage");
  c.push_back("contact_energy");
  return c;
}

std::vector<double> PdSolver::history_values() const {
  std::vector<double> v = loads_.history_values(scenario_);  // indenter reactions: sums over points
  comm_.sum(v.data(), static_cast<int>(v.size()));
  for (double& f : v) f *= thickness_;  // 2D: per unit thickness -> the plate's
  const auto* damage = points_.real(pd::kBondDamage);
  // The mean damage is of the solids (gas points have no bonds to break).
  const std::uint8_t* gas = skip_gas();
  double e[3];
  deterministic_sum<3>(0, points_.size(), [&](Index p, double* o) {
    const bool solid = !(gas && gas[p]);
    o[0] += solid ? damage[p] : 0.0;
    o[1] += contact_energy_[local_.own[p]];
    o[2] += solid ? 1.0 : 0.0;
  }, e);
  const double count = comm_.sum(e[2]);
  v.push_back(static_cast<double>(broken_bonds()));
  v.push_back(count > 0.0 ? comm_.sum(e[0]) / count : 0.0);  // mean over points (LAMMPS compute reduce ave)
  v.push_back(thickness_ * comm_.sum(e[1]));
  return v;
}

std::vector<ResultTable> PdSolver::result_tables() const {
  // fragments.csv: the snapshots every fragment_interval, then the fragments at the end (unless the
  // last snapshot was taken at the end already).
  ResultTable t{"fragments",
                {"time", "fragment", "points", "mass", "x", "y", "z", "vx", "vy", "vz", "speed", "kinetic_energy"},
                fragment_rows_};
  if (t.rows.empty() || t.rows.back()[0] != time_) {
    // Rank 0 only: the rows result_values() found (collective), or on one rank found now.
    auto now = final_rows_time_ == time_ ? final_rows_ : fragment_rows(fragments());
    t.rows.insert(t.rows.end(), now.begin(), now.end());
  }
  return {t};
}

namespace {

std::unique_ptr<Solver> make_pd(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials,
                                const Communicator& comm) {
  return std::make_unique<PdSolver>(sc, std::move(materials), comm);
}

}  // namespace

}  // namespace ballista

BALLISTA_REGISTER_SOLVER(ballista::SolverFactory{
    .name = "peridynamics",
    .description = "bond-based peridynamics, PMB bonds with critical stretch (Silling & Askari 2005; EMU, seed 001)",
    .dimensions = {"3d", "plane_strain", "plane_stress"},
    .section = "peridynamics",
    .params = ballista::pd_params(),
    .create = &ballista::make_pd,
    .distributed = true,
    .face_conditions = {ballista::FaceBC::Free},
    .face_conditions_note =
        "the box only bounds where points may go: a symmetry plane or fixed face would need mirror or frozen ghost "
        "points across it, which the bond families do not have yet; model the whole body, or hold points with a "
        "rigid indenter (loads: indenter)",
    .point_spacing = true,
    .pre_cracks = true,
    .background_grid = false})
