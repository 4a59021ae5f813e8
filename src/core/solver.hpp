#pragma once
// What the run loop needs from any discretisation (MPM, peridynamics, OTM).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/field_store.hpp"
#include "core/state_archive.hpp"
#include "core/tensor.hpp"

namespace ballista {

/// Global energy and momentum totals (already reduced over ranks). In axisymmetric runs the
/// values are for the full body of revolution (per-radian sums times 2 pi); in plane strain per
/// metre of thickness.
struct EnergyTotals {
  double kinetic = 0.0;        ///< J
  double internal = 0.0;       ///< J, accumulated stress power (elastic + plastic)
  double plastic = 0.0;        ///< J, accumulated plastic dissipation
  double eroded = 0.0;         ///< J, the part of `internal` held by failed (eroded) points
  double external = 0.0;       ///< J, accumulated work of body forces and surface loads
  double mass = 0.0;           ///< kg
  Vec3 momentum;               ///< kg m/s
  double removed_mass = 0.0;   ///< kg carried off by deleted particles
  double removed_energy = 0.0; ///< J (kinetic + internal) carried off by deleted particles
  Vec3 removed_momentum;       ///< kg m/s carried off by deleted particles
  /// Per body (deck order): points deleted, and the mass (kg) and kinetic + internal energy (J)
  /// they carried off; and each body's seeded mass (kg), to tell how much of it is gone.
  std::vector<double> removed_points_by_body, removed_mass_by_body, removed_energy_by_body, seeded_mass_by_body;
  double inserted_energy = 0.0;  ///< J (kinetic + internal) brought in by bodies activated after t = 0
  /// J, chemical energy released so far by burning explosive (deleted points included). Not a
  /// term of total(): the products' energy enters the stress-power integral `internal` as the work
  /// they do, so the balance closes without it; it is the energy scale of an explosive run.
  double chemical = 0.0;
  // Work done on the points by the discretisation itself (J; negative when it removes energy),
  // booked so that the balance closes. Zero for solvers that have no such term.
  double damping = 0.0;   ///< grid damping -c m v (stages and simulation.damping)
  double contact = 0.0;   ///< multi-field grid contact (normal and frictional impulses)
  double friction = 0.0;  ///< the frictional part of `contact` (already inside it)
  /// particle-grid transfer: the PIC share of the FLIP/PIC update (usl, musl), the whole
  /// particle-minus-grid kinetic energy change (usavg)
  double transfer = 0.0;
  double boundary = 0.0;  ///< the grid face and axis conditions' impulses on the nodes
  /// J, the heat of the artificial bulk viscosity (MPM, mpm.bulk_viscosity_*): a breakdown of
  /// `internal`, like `plastic`, not a separate term of total().
  double viscous = 0.0;
  /// Energy balance: kinetic + internal + removed - external - inserted - the discretisation's
  /// booked work; constant in an exact solution, and its change is the unexplained residual.
  double total() const {
    return kinetic + internal + removed_energy - external - inserted_energy - damping - contact - transfer - boundary;
  }
};

/// The point that sets the stable time step (largest c + |v|, over its cell where cells differ):
/// for diagnosing a collapsing step.
struct StepLimiter {
  std::int64_t id = -1;        ///< particle id (-1: none)
  int body = -1;               ///< body index in deck order
  double wave_speed = 0.0;     ///< m/s, its signal speed: the dilatational wave speed, or the bulk viscosity's
  double speed = 0.0;          ///< m/s, |v|
  double J = 1.0;              ///< det F
  double cell = 0.0;           ///< m, the cell length its signal crosses (MPM; 0 if not given)
  bool viscous = false;        ///< wave_speed is the bulk viscosity's Q + sqrt(Q^2 + c^2) (MPM)
  /// Its signal rate over that of the fastest point outside the fastest thousandth of the points:
  /// how much larger the step would be without those few (MPM on one rank; 0: not computed).
  double margin = 0.0;
  /// The point updates of one step over those of the same interval with every point stepped at
  /// its own stable step, rounded down to a power-of-two multiple of this one (at most
  /// 2^kMultirateLevels): what a per-point (multi-rate) step would save in point updates, grid
  /// work not counted (MPM on one rank; 0: not computed).
  double multirate = 0.0;
};

/// The coarsest class of StepLimiter::multirate: 64 times the stable step.
inline constexpr int kMultirateLevels = 6;

/// A table a solver adds to a run's results, written as `<name>.csv` in the results folder.
struct ResultTable {
  std::string name;                        ///< file stem, e.g. "fragments"
  std::vector<std::string> columns;        ///< header
  std::vector<std::vector<double>> rows;   ///< one value per column
};

class Solver {
 public:
  virtual ~Solver() = default;
  virtual const char* name() const = 0;
  /// Largest stable time step for the current state (global minimum over ranks), s.
  virtual double stable_dt() = 0;
  /// Advances the state by dt; throws PhysicsError on NaN, inverted points or lost particles.
  virtual void step(double dt) = 0;
  /// A step of up to dt (the stable step, already counted in the run's statistics), shortened to
  /// end on an event of the solver's own it would otherwise cross (MPM multi-rate: a pending
  /// activation time); dt itself if none.
  virtual double land_step(double dt) const { return dt; }
  virtual double time() const = 0;
  virtual long steps() const = 0;
  /// The points of this rank (fields named as the output datasets).
  virtual FieldStore& points() = 0;
  /// A second point cloud written beside the points at every output (the OTM nodes: x, v, mass),
  /// brought up to date by this call; null for solvers without one.
  virtual const FieldStore* output_nodes() { return nullptr; }
  /// Points seeded but not active yet (bodies with a later activation); ids run over both.
  virtual Index pending_points() const { return 0; }
  virtual EnergyTotals energies() const = 0;
  /// Multiplier turning per-point sums into physical totals (2 pi in axisymmetric runs).
  virtual double reporting_scale() const = 0;
  /// Starts stage `stage` (0 = first; preparation stages, then the main stage) at the current
  /// time: bodies activated by that stage start their clocks now, and the grid damping becomes
  /// `damping` (1/s, thesis seed 000 eq. 5.1).
  virtual void begin_stage(int stage, double damping) = 0;
  /// The point with the largest c + |v| now (one pass over the points; call it rarely).
  virtual StepLimiter step_limiter() const { return {}; }
  /// Constants derived from the deck, as YAML comment lines appended to resolved.yaml ("" if none).
  virtual std::string derived_constants() const { return {}; }
  /// Extra history.csv columns of this solver and its loads (indenter reactions, contact energy).
  virtual std::vector<std::string> history_columns() const { return {}; }
  /// Their values now (same order and count as history_columns()).
  virtual std::vector<double> history_values() const { return {}; }
  /// Results of this discretisation at the end of a run, for summary.json ("solver_results").
  virtual std::vector<std::pair<std::string, double>> result_values() const { return {}; }
  /// Wall seconds per phase of the step so far, for summary.json ("timing") and the benchmarks;
  /// kept apart from the results so that two identical runs give identical solver_results.
  virtual std::vector<std::pair<std::string, double>> timing_values() const { return {}; }
  /// Tables of this discretisation written at the end of a run (e.g. fragments.csv).
  virtual std::vector<ResultTable> result_tables() const { return {}; }

  // ---- checkpoint and restart (docs/restart.md) ----------------------------------------------
  /// Puts everything the next step depends on into `archive` (points, pending bodies, solver
  /// state, booked energies, time and step), so that load_state on a solver built from the same
  /// deck continues bitwise as this one would.
  virtual void save_state(StateArchive& archive) const {
    (void)archive;
    throw Error(std::string("the ") + name() + " solver cannot write checkpoints yet");
  }
  /// Restores what save_state wrote; throws Error naming a missing or mis-sized key.
  virtual void load_state(const StateArchive& archive) {
    (void)archive;
    throw Error(std::string("the ") + name() + " solver cannot restart from a checkpoint yet");
  }
};

}  // namespace ballista
