#pragma once
// What every discretisation shares about its points (MPM particles, peridynamic points, OTM
// material points), so that a solver owns only its own discretisation: seeding the scenario's
// bodies and segments on a lattice, activation by time and stage, material groups and the stress
// update through the material library, removal with its mass, momentum and energy booked,
// failure diagnostics naming the point, and the energy totals.
#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"
#include "core/solver.hpp"
#include "core/state_archive.hpp"
#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// The lattice the bodies are seeded on: sub-cell centres lattice.lower + (i + 1/2) dx with
/// dx = lattice.cell_size / particles_per_cell (each body's own, unless override_ppc > 0), inside
/// the box lattice.lower .. lattice.upper (whose face conditions excuse symmetry-plane cuts).
struct SeedLattice {
  GridSpec box;
  int override_ppc = 0;  ///< > 0: every body seeded with this many points per cell and direction
  double solver_bytes_per_point = 0.0;  ///< the solver's own storage per point (bonds), for the memory estimate
};

class PointSet {
 public:
  /// Declares the common and material fields, checks that the points (plus `solver_bytes` of the
  /// solver's own storage) fit in memory, seeds every body, applies initial states, marks the
  /// pressure surfaces and moves bodies with a later activation into the pending store.
  PointSet(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, const SeedLattice& lattice,
           double solver_bytes, const std::string& memory_what, Communicator comm = {});

  FieldStore& store() { return points_; }
  const FieldStore& store() const { return points_; }
  const Scenario& scenario() const { return scenario_; }
  /// Declares a solver's own real field on the active and the pending points (zero-initialised).
  void add_real(const std::string& name, int ncomp, const std::string& unit, bool output = true) {
    points_.add_real(name, ncomp, unit, output);
    pending_.add_real(name, ncomp, unit, output);
  }
  /// The same through a key: the shape comes from its type.
  template <class T>
  void declare(const FieldKey<T>& key, const std::string& unit, bool output = true) {
    points_.declare(key, unit, output);
    pending_.declare(key, unit, output);
  }
  const std::vector<std::unique_ptr<Material>>& materials() const { return materials_; }
  /// Fields the loads marked on the points (a pressure's "load_area_<k>"): extensive, so a point
  /// that splits shares them.
  const std::vector<std::string>& load_area_fields() const { return load_area_fields_; }

  /// Several ranks: every rank seeded every body; it keeps its contiguous share (by index) of
  /// the active and of the pending points, and the solver's partition then moves them to their
  /// owners. Mass, momentum and energy totals are sums over the ranks (energies()).
  void keep_share(const Communicator& comm);
  /// Several ranks: keeps the active points with keep[p] != 0 (a solver's own partition of every
  /// rank's full seeding: peridynamics), without booking anything as removed. No pending points.
  void keep(const std::vector<char>& keep);
  /// Several ranks: keeps the active points with keep[p] != 0, in their order, and the contiguous
  /// share of the pending points (as keep_share).
  void keep_share(const Communicator& comm, const std::vector<char>& keep);
  const Communicator& communicator() const { return comm_; }

  // ---- activation --------------------------------------------------------------------------
  /// Number of points seeded but not yet active.
  Index pending() const { return pending_.size(); }
  /// Starts the clock of stage `stage` at `time` (bodies activated by it count from now).
  void begin_stage(int stage, double time);
  /// Moves pending points whose activation time has come into the store (appended at the end),
  /// booking their kinetic and internal energy as inserted. True if any point was added.
  bool activate(double time);
  /// The earliest activation time of a pending point later than `time` (infinite if none is
  /// known: no pending points, or their stages have not begun).
  double next_activation(double time) const;
  /// s: when the main stage began (infinite before it).
  double main_stage_start() const { return stage_start_.back(); }
  /// True if a pending point's activation time is `time` or earlier (it enters at the next step).
  bool activation_due(double time) const;

  // ---- material groups and the stress update -----------------------------------------------
  /// The points have been reordered or removed: material groups are rebuilt before next use.
  void mark_reordered() { groups_dirty_ = true; }
  /// Indices of the points of each material, in point order.
  const std::vector<std::vector<Index>>& material_groups();
  /// The points of material m's group that lie in [begin, end) (a group lists its points in order).
  std::span<const Index> material_points_in(std::size_t m, Index begin, Index end) {
    const std::vector<Index>& g = material_groups()[m];
    const Index* first = std::lower_bound(g.data(), g.data() + g.size(), begin);
    return {first, std::lower_bound(first, g.data() + g.size(), end)};
  }
  /// Largest c + |v| over this rank's points (c the dilatational wave speed of each material).
  double max_signal_speed();
  /// The point with the largest c + |v| (per point through the virtual wave speed: diagnostics).
  /// Several ranks (collective): the rank with the fastest signal names its point to all.
  StepLimiter step_limiter() const;
  /// Sets c[p] = 0 for every point that failed and whose material's failed points carry no stress
  /// (erosion zero_stress, thesis seed 000 eq. 6.13-6.14): such a point has no stiffness and its
  /// deformation is frozen, so no stress wave crosses it, and the sound speed of its frozen state
  /// (often hot and distended at failure) bounds nothing. A no-op without such a material.
  void zero_wave_speeds_of_stress_free(double* c) const;
  /// Stress update of every point through its material, from F (already at t_{n+1}) and L over dt;
  /// stress power and plastic work accumulate in internal_energy and plastic_work. A non-finite
  /// stress stops the run with fail(). With `only` given, just the materials m with only[m] != 0
  /// (peridynamics: its gas; the solids' stress is their bonds'); the points [begin, end) only
  /// (end < 0: to the last; MPM's multi-rate stepping updates its two classes apart).
  void update_stress(double dt, long step, double time, const std::vector<std::uint8_t>& only = {}, Index begin = 0,
                     Index end = -1);
  /// The stress update remaps F of points beyond this RMS isochoric stretch (MaterialBatch::
  /// distortion_limit, materials/distortion.hpp); 0: never (the default).
  void set_distortion_limit(double limit) { distortion_limit_ = limit; }
  /// Remaps so far, summed over the ranks (collective).
  std::int64_t distortion_remaps() const;
  /// Inverting increments of stress-free eroded points that a solver discarded (their F is frozen,
  /// thesis eq. 6.14), summed over the ranks; kept in checkpoints.
  std::int64_t frozen_increments_discarded() const;
  void add_frozen_increments_discarded(std::int64_t n) { frozen_discarded_ += n; }
  /// True if point p has failed and its material's failed points carry no stress (erosion
  /// zero_stress: its F is frozen, thesis eq. 6.14). Looks its fields up: not for a per-point loop.
  bool failed_stress_free(Index p) const;

  // ---- removal and diagnostics -------------------------------------------------------------
  /// Keeps the points with keep[p] != 0; the others' mass, momentum and kinetic + internal energy
  /// are booked as removed.
  void remove(const std::vector<char>& keep);
  /// Books point p's kinetic and internal energy and its momentum as removed while the point
  /// stays in the store (peridynamic gas vented from the box: its bonds cannot be compacted away);
  /// the caller then zeroes its velocity and internal energy so that nothing is counted twice.
  void book_vented(Index p);
  /// Throws a ParticleError naming point p (id, body, position, F, J, stress), the step and time.
  [[noreturn]] void fail(Index p, const std::string& what, long step, double time) const;

  // ---- energies ----------------------------------------------------------------------------
  /// Totals over every rank: per-point sums times `scale` (2 pi in axisymmetric runs), with the
  /// solver's external work (per-point sum) and the removal and insertion bookkeeping.
  EnergyTotals energies(double scale, double external_work) const;

  // ---- checkpoint and restart --------------------------------------------------------------
  /// Active and pending points, activation clocks, stage starts and the removal and insertion
  /// bookkeeping, under "points." and "pending." (core/state_archive.hpp). Several ranks
  /// (collective): the archive of rank 0 holds every rank's points in rank order, each rank's
  /// count and bookkeeping, and the totals, i.e. a checkpoint any rank count can read.
  void save_state(StateArchive& archive) const;
  /// Restores them into a PointSet built from the same deck; material groups are rebuilt. Several
  /// ranks: a checkpoint written on as many ranks gives each rank its own points back in their
  /// order (true: the caller keeps its decomposition); any other gives each rank a contiguous share
  /// and the totals to rank 0 (false: the caller repartitions).
  bool load_state(const StateArchive& archive);
  /// Exactly the active points whose ids are in `ids` (sorted), in id order, from a checkpoint
  /// written on any rank count (a solver whose partition is fixed by the deck: peridynamics). True
  /// if the checkpoint was written on as many ranks (each rank's removal bookkeeping back), else
  /// the totals go to rank 0.
  bool load_state(const StateArchive& archive, const std::vector<std::int64_t>& ids);

 private:
  /// Keeps active points [first, last) and pending points [first_pending, last_pending).
  void keep_ranges(Index first, Index last, Index first_pending, Index last_pending);
  void keep_with_pending(std::vector<char> keep, Index first_pending, Index last_pending);
  /// Several ranks: the checkpoint was written on this many ranks (each rank's share is in it).
  bool written_on_as_many_ranks(const StateArchive& archive) const;
  /// The removal and insertion bookkeeping from a checkpoint: this rank's own (`own`), else the
  /// totals on rank 0 and zeros elsewhere (counted once).
  void restore_removed(const StateArchive& archive, bool own);

  Scenario scenario_;
  std::vector<std::unique_ptr<Material>> materials_;
  Communicator comm_;
  FieldStore points_;
  FieldStore pending_;                      ///< seeded points of bodies not yet active
  std::vector<double> pending_activation_;  ///< activation time of each pending point (from its stage start)
  std::vector<int> pending_stage_;          ///< stage whose start begins each pending point's clock
  /// s: when pending point p enters (infinite while its stage has not begun).
  double activation_time(Index p) const {
    return stage_start_[static_cast<std::size_t>(pending_stage_[static_cast<std::size_t>(p)])] +
           pending_activation_[static_cast<std::size_t>(p)];
  }
  std::vector<double> stage_start_;         ///< s: start time of each stage (infinite until it begins)
  std::vector<std::vector<Index>> material_points_;  ///< indices per material
  bool groups_dirty_ = true;
  std::vector<std::string> load_area_fields_;
  /// The removal and insertion bookkeeping as one record (checkpoints sum and split it by rank):
  /// mass, energy, chemical energy, momentum (3), inserted energy, then per body the points, mass
  /// and energy deleted.
  std::vector<double> removal_record() const;
  double removed_mass_ = 0.0, removed_energy_ = 0.0;
  std::vector<double> removed_points_body_, removed_mass_body_, removed_energy_body_;  ///< this rank's, per body
  std::vector<double> seeded_mass_body_;  ///< kg per body (deck order), every rank's points
  double removed_chemical_ = 0.0;  ///< J, chemical energy released by points since deleted
  Vec3 removed_momentum_;
  double inserted_energy_ = 0.0;  ///< per-point sum of the energy of activated points (this rank)
  double distortion_limit_ = 0.0;
  std::int64_t distortion_remaps_ = 0;  ///< this rank's (a restart gives the total to rank 0)
  std::int64_t frozen_discarded_ = 0;   ///< this rank's (a restart gives the total to rank 0)
};

}  // namespace ballista
