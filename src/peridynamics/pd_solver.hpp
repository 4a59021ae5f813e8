#pragma once
// Bond-based peridynamics (Silling, JMPS 48 (2000) 175; Silling & Askari, Comput. Struct. 83
// (2005) 1526), the discretisation of Sandia's EMU code (seed 001_65d50031991c2cdb.txt: "EMU
// numerical method"): points on a regular lattice, each interacting with every point of its
// family (within the horizon delta) through a pairwise force; explicit velocity Verlet.
//
// Material model (seed 001, "Microelastic material"): the prototype microelastic brittle (PMB)
// bond, f = c s (eta + xi)/|eta + xi| per unit volume squared, s = (|eta + xi| - |xi|)/|xi|,
// c = 18 K/(pi delta^4) in 3D (Silling & Askari 2005 eq. 22). K is the bulk modulus of the point's
// material from the shared library (probed through its own kernel). A bond breaks for good when
// its stretch exceeds s0 = min(s0_i, s0_j), s0_i = s00 - alpha s_min,i (LAMMPS PERI's rule, the
// previous step's smallest stretch of point i), s00 given or from the fracture energy G0:
// s00 = sqrt(5 G0/(9 K delta)) (Silling & Askari 2005 eq. 25). Damage of a point is the
// volume-weighted fraction of its broken bonds (seed 001, "Damage").
// With formulation: lps the bonds carry the state-based linear peridynamic solid instead (any
// Poisson's ratio; lps_pass.hpp), with the same families, failure rule, damage and contact.
//
// The points layer (seeding, loads, removal, energies, diagnostics) is shared with MPM: this file
// owns only the bonds, the force and the time integration.
//
// Several MPI ranks (peridynamics/pd_halo.hpp): the points are partitioned once by RCB of
// their reference positions; the bond pass runs over each rank's own points and ghost copies in
// the local numbering of pd_halo.hpp. Arrays named per local point are indexed by that numbering,
// the point fields (the store) by the own points' order; local_.own maps the one to the other (the
// identity on one rank). Detonation products (the gas) have their own ghosts: the gas family's
// neighbours, their push G exchanged after the products' update (pd_gas.cpp).
#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "core/communicator.hpp"
#include "core/solver.hpp"
#include "materials/material.hpp"
#include "peridynamics/bond_constants.hpp"
#include "peridynamics/bond_family.hpp"
#include "peridynamics/contact_list.hpp"
#include "peridynamics/fragments.hpp"
#include "peridynamics/gas_pass.hpp"
#include "peridynamics/pd_halo.hpp"
#include "peridynamics/pd_params.hpp"
#include "points/point_loads.hpp"
#include "points/point_set.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class PdSolver final : public Solver {
 public:
  PdSolver(const Scenario& scenario, std::vector<std::unique_ptr<Material>> materials, Communicator comm = {});

  const char* name() const override { return "peridynamics"; }
  double stable_dt() override;
  void step(double dt) override;
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  FieldStore& points() override { return points_; }
  Index pending_points() const override { return pts_.pending(); }
  EnergyTotals energies() const override;
  double reporting_scale() const override { return thickness_; }
  void begin_stage(int stage, double damping) override;
  StepLimiter step_limiter() const override { return pts_.step_limiter(); }
  /// broken_bonds, fragment_count, largest_fragment_mass (kg), mean_fragment_mass (kg), max_damage,
  /// bond_build_seconds, contact_list_builds, bytes_per_bond_end.
  std::vector<std::pair<std::string, double>> result_values() const override;
  /// fragments.csv: one row per fragment, largest first (peridynamics/fragments.hpp).
  std::vector<ResultTable> result_tables() const override;
  /// Horizon, and per material pair the micromodulus c and critical stretch s00.
  std::string derived_constants() const override;
  /// Indenter reactions, then broken_bonds, mean_damage and contact_energy (J, in the contact springs).
  std::vector<std::string> history_columns() const override;
  std::vector<double> history_values() const override;

  /// Checkpoint (pd_checkpoint.cpp): the points, the broken flags and plastic stretches of the
  /// bonds (each point's row in id order of its neighbours), the positions of the last contact
  /// list build (the list is rebuilt from them), the critical stretches, the gas state, the energy
  /// bookkeeping and the fragment snapshots. The bond families and constants are rebuilt from
  /// the deck by the constructor (deterministic), so they are not stored. Several ranks: every
  /// rank's rows and values gathered to rank 0 in the points' order, a checkpoint any rank count
  /// (and a serial run) reads.
  void save_state(StateArchive& archive) const override;
  /// Wall time of the bond families and their solver arrays (summary.json timing.bond_build_seconds).
  std::vector<std::pair<std::string, double>> timing_values() const override {
    return {{"bond_build", bond_build_seconds_}};
  }
  void load_state(const StateArchive& archive) override;

  /// The bonds of the local points (one rank: every point, in store order).
  const pd::BondFamily& bonds() const { return bonds_; }
  const pd::ContactList& contacts() const { return contact_; }
  double horizon() const { return delta_; }
  /// Micromodulus c of the bond between points of materials a and b, N/m^6.
  double micromodulus(int a, int b) const { return c_[a * nmat_ + b]; }
  /// s_y of the micro-plastic bonds (infinite: elastic bonds).
  double yield_stretch() const { return yield_stretch_; }
  /// Critical stretch s00 of the bond between materials a and b (infinite: no failure).
  double critical_stretch(int a, int b) const { return s00_[a * nmat_ + b]; }
  /// s00 of point p (the smallest over its family's material pairs, times its stretch_scatter factor).
  double point_critical_stretch(Index p) const { return s00_point_[p]; }
  /// Bonds broken so far (each counted once; over every rank, collective).
  Index broken_bonds() const;
  /// Re-evaluates the bond forces, energies and damage at the current positions without advancing
  /// time (after positions were set from outside, e.g. by a test imposing a deformation).
  void refresh();
  /// Breaks, before the run, every bond whose reference end points (x0 of its two ends) satisfy
  /// `cut(x0_p, x0_q)` (a pre-crack or notch: the crack faces start stress-free, nothing is
  /// dissipated), then refreshes forces and damage. Returns the number of bonds broken.
  Index break_bonds(const std::function<bool(const Vec3&, const Vec3&)>& cut);

 private:
  /// Marks broken every intact bond p-q with cut(p, q) or cut(q, p), at both ends, with nothing
  /// dissipated (pre-cracks); returns how many bonds. Forces are not re-evaluated.
  Index cut_bonds(const std::function<bool(Index, Index)>& cut);
  // Construction (pd_solver.cpp, pd_bond_setup.cpp), in the order the constructor calls them.
  /// The lattice, horizon, thickness and damping, and what the solver refuses of the rest of the
  /// deck (an explosive in plane stress, bodies activated later, deleted points).
  void read_settings(const Scenario& sc);
  /// Which materials are a peridynamic gas (explosives), and the point fields that mean nothing
  /// here left out of the output.
  void classify_materials(const Scenario& sc);
  /// Each body's lattice spacing over dx (bodies[].point_spacing: only the products' may differ).
  void read_body_scales(const Scenario& sc);
  /// Micromodulus, critical stretch and contact stiffness per material pair, and the yield stretch
  /// of micro-plastic bonds, from each solid's probed moduli (bond_constants.hpp).
  void set_bond_constants(const Scenario& sc);
  /// The partition (several ranks), the local points with their ghosts and the bond family of the
  /// local points (pd_halo.hpp); one rank: the family of every point.
  void build_local_points();
  /// Each point's critical stretch: the smallest over its family's material pairs, scattered by
  /// stretch_scatter.
  void init_critical_stretch();
  /// What the half-bond force pass needs besides the bonds (damage denominators, row splits,
  /// mirrors, blocks of ids).
  void build_bond_tables();
  /// surface_correction: energy, each point's factor m1/m1_p (bond_constants.hpp).
  void apply_surface_correction();
  /// Each point's bond stiffness of the stable step.
  void set_bond_stiffness();
  /// Pre-cracks (deck `cracks`): the bonds whose ends lie on either side of each segment.
  void cut_pre_cracks(const Scenario& sc);
  /// Own points' positions into the local copies, and the ghosts' from their owners (collective);
  /// the ghosts' previous positions become their step-start positions.
  void sync_local();
  /// True on every rank if some own point moved more than skin/2 since the last build (collective).
  bool contacts_stale() const;
  /// Builds the contact list at the current local positions (several ranks: with the contact
  /// ghosts gathered anew; collective).
  void rebuild_contacts();
  /// Per-local-point solver arrays to the current local point count (contact ghosts changed).
  void resize_local_arrays();
  /// The fragments now (several ranks: found on rank 0 over every rank's points and intact bonds,
  /// empty elsewhere; collective).
  std::vector<pd::Fragment> fragments() const;
  /// Bond forces (per unit mass, into field pd_accel), stretches, failures, s0 for the next step,
  /// damage and the per-point bond energies.
  void compute_forces();
  // ---- the linear peridynamic solid (formulation: lps; lps_pass.hpp, pd_lps.cpp) --------------
  /// K and mu of each solid, the micromodulus of its equivalent PMB bond (stable step, contact
  /// springs) and the critical stretch per material pair.
  void set_lps_constants(const Scenario& sc);
  /// The weighted volume of every local point (ghosts' from their owners).
  void build_lps_weighted_volumes();
  /// The state-based forces, energies, failures and dissipation into acc_ (collective: the
  /// ghosts' force-state coefficients come from their owners).
  void lps_pass();
  /// One step of this rank (step() agrees on failures across ranks).
  void advance(double dt);

  // ---- detonation products as a peridynamic gas (gas_pass.hpp, pd_gas.cpp) -------------------
  /// The gas family of the explosive points and their neighbours, V_i and the stable-step sums.
  void build_gas();
  pd::GasPassArgs gas_pass_args() const;
  /// X of every gas point at the current positions, F = X^(1/d) I and L over dt, the material's
  /// update at t + dt (burn, pressure, -P dV booked as internal energy), then G_i for the forces.
  void update_gas(double dt);
  /// The gas family renewed at the current positions and X (peridynamics.gas_refamily_steps,
  /// pd::build_renewed_gas_family), its inputs kept for a checkpoint.
  void refamily_gas();
  /// The family from the kept inputs (renewal_), with the gas points' family volumes and stable
  /// step sums (also on restart).
  void build_renewed_gas_family();
  /// Smallest stable step of the gas points: Silling & Askari's bound with the micromodulus of
  /// the products' current bulk modulus rho c^2.
  double gas_stable_dt() const;
  /// Gas points that left the box: their kinetic and internal energy and momentum booked as
  /// removed; they fly on at the velocity they left with (kept apart from the field v, which is
  /// zeroed so that the energies do not count them), without pressure, so that their neighbours
  /// still near the box see them move away rather than pile up at the box face.
  void vent_escaped_gas();
  /// 1 for every gas point of the store (fragments are of the solids only); null without gas.
  const std::uint8_t* skip_gas() const { return has_gas_ ? gas_.data() : nullptr; }
  /// 1 for every vented gas point, per local point (out of the contact list); null without gas.
  const std::uint8_t* skip_vented() const { return has_gas_ ? vented_.data() : nullptr; }

  Scenario scenario_;
  const PdParams params_;       ///< the peridynamics section, read and checked before seeding
  Communicator comm_;
  PointSet pts_;
  FieldStore& points_;
  PointLoads loads_;
  bool loads_current_ = false;  ///< loads_ holds the loads at the current positions and time
  pd::BondFamily bonds_;        ///< rows of the local points [0, local_.bond_local)
  pd::LocalPoints local_;       ///< own points and ghosts (pd_halo.hpp)
  pd::PdHalo halo_;
  Index global_points_ = 0;     ///< points over every rank
  double dx_ = 0.0, delta_ = 0.0;
  int dim_ = 3;             ///< 3, or 2 (plane strain / plane stress: points in the x-y plane)
  double thickness_ = 1.0;  ///< m, 2D: totals (energies, masses) are per this thickness
  int nmat_ = 0;
  std::vector<double> c_;    ///< micromodulus per material pair, N/m^6
  std::vector<double> s00_;  ///< critical stretch per material pair (inf: no failure)
  std::vector<double> c_contact_;  ///< micromodulus of the contact springs per material pair
                                   ///< (gas-solid: the solid's), N/m^6
  double damping_ = 0.0;     ///< 1/s: a - c v (dynamic relaxation, stages)
  double yield_stretch_ = std::numeric_limits<double>::infinity();  ///< s_y of micro-plastic bonds
  std::vector<double> sp_;             ///< per bond end: the micro-plastic stretch (both ends equal) or the
                                       ///< LPS plastic extension of that end, m (empty: elastic)
  std::vector<double> surface_factor_; ///< per point m1/m1_p (surface_correction: energy; empty: off)
  std::vector<Index> upper_;           ///< first bond of each row whose other end has a higher index
  std::vector<std::int32_t> mirror_;   ///< each bond's position in its other end's row
  std::vector<double> inv_len0_;       ///< 1/|xi| per bond (the force loop multiplies instead of dividing)
  std::vector<Index> block_start_;     ///< blocks of points of the half-bond pass (compute_forces)
  /// Per-point sums of one force evaluation (each bond adds to both ends).
  struct Acc {
    std::vector<Vec3> f;                 ///< N
    std::vector<double> energy, dis, vol_broken, smx, e_contact, k_contact;
    void resize(Index n) {
      const auto m = static_cast<size_t>(n);
      f.resize(m), energy.resize(m), dis.resize(m), vol_broken.resize(m), smx.resize(m), e_contact.resize(m),
          k_contact.resize(m);
    }
    void clear(Index p) {
      f[p] = Vec3{};
      energy[p] = dis[p] = vol_broken[p] = e_contact[p] = k_contact[p] = 0.0;
      smx[p] = -std::numeric_limits<double>::infinity();
    }
  };
  Acc acc_;
  std::vector<double> lps_bulk_, lps_shear_;  ///< per material: K and mu of the LPS solid, Pa
  std::vector<double> lps_m_;                 ///< per local point: weighted volume, m^5
  std::vector<double> lps_alpha_;             ///< per local point: 15 mu / m, Pa/m^5
  /// Per local point (lps_pass.hpp): theta, B, the elastic part of S and whether a bond breaks,
  /// with this evaluation's failures and before them.
  std::vector<double> lps_theta_, lps_theta_old_, lps_coef_, lps_coef_old_, lps_s_, lps_s_old_, lps_breaks_;
  std::vector<double> lps_length_;  ///< per bond end, with plasticity: |y| of the last evaluation, m
  std::vector<double> lps_td_;      ///< per bond end, with plasticity: t^d after the last evaluation
  double bond_build_seconds_ = 0.0;  ///< wall time of the bond families and their solver arrays, s
  std::vector<double> vol_all_;        ///< sum_j beta V_j of each point's family (damage denominator), m^3
  std::vector<double> stiff_bond_;     ///< sum_j V_j c/|xi| of each point's bonds (reference), N/m^4
  std::vector<double> stiff_contact_;  ///< sum of c_s V_q over each point's active contacts, N/m^4
  std::vector<double> s0_;         ///< current critical stretch of each point
  std::vector<double> s00_point_;  ///< s00 of each point (smallest over its family's material pairs)
  std::vector<double> s0_next_;    ///< scratch: s0 of the next step
  std::vector<Vec3> v_half_;       ///< scratch: v_{n+1/2} of the step (external work)
  std::vector<Vec3> x_prev_;       ///< positions at the start of the step (energy of breaking bonds)
  std::vector<Vec3> f0_;           ///< scratch: external forces at the step's start
  std::vector<double> dissipated_; ///< J: energy of the broken bonds, half of each to each end
  pd::ContactList contact_;          ///< never-bonded pairs near each other
  std::vector<double> contact_energy_;  ///< J: each point's half of its contact springs' energy
  double next_fragment_time_ = 0.0;
  std::vector<std::vector<double>> fragment_rows_;  ///< snapshots so far (fragments.csv rows)
  /// fragments.csv rows of `frags` (time, fragment, points, mass, centre, velocity, speed, KE).
  std::vector<std::vector<double>> fragment_rows(const std::vector<pd::Fragment>& frags) const;
  /// The rows at the end, found by result_values() (collective) for result_tables() (rank 0 only).
  mutable std::vector<std::vector<double>> final_rows_;
  mutable double final_rows_time_ = -1.0;
  std::vector<std::uint8_t> gas_material_;  ///< per material: an explosive (a peridynamic gas)
  std::vector<std::uint8_t> gas_;           ///< per own point (store order): 1 for gas points
  std::vector<std::uint8_t> gas_local_;     ///< per local point: 1 for gas points
  bool has_gas_ = false;
  double m1_ = 0.0;                   ///< the family moment m1 of the bond constants (gas stable step)
  std::vector<double> body_scale_;    ///< per body: its lattice spacing over dx (point_spacing; 1 by default)
  double max_scale_ = 1.0;            ///< the largest of them
  std::vector<double> gas_scale_;     ///< per local point: its body's scale for gas, 1 for solids
  pd::BondFamily gas_bonds_;          ///< build_gas_family
  std::vector<double> gas_len_other_; ///< after refamily_gas: the other end's reference length per row entry, m
  std::vector<float> gas_weight_other_;  ///< after refamily_gas: this end's weight in the other end's measure
  pd::RenewedGasFamily gas_spare_;    ///< the family before the current one: storage for the next renewal
  pd::GasRenewalWorkspace gas_workspace_;  ///< the renewal search's buffers, kept between renewals
  long gas_renewals_ = 0;             ///< renewals so far (result value)
  /// The inputs of the last renewal of the gas family, per local point (empty before the first).
  struct GasRenewal {
    std::vector<Vec3> x;               ///< positions, m
    std::vector<double> X;             ///< density measures
    std::vector<std::uint8_t> skip;    ///< vented then
  } renewal_;
  // Per local point (own points' values; a ghost's G and vented flag come from its owner).
  std::vector<double> gas_volume_;    ///< V_i = sum_j beta dV_j of each gas point, m^3
  std::vector<double> gas_inv_len_;   ///< sum_j beta dV_j / |xi| of each gas point, 1/m^2
  struct GasStepScratch {  ///< gas_stable_dt's lists, per material, kept between steps
    std::vector<std::vector<Index>> points;
    std::vector<std::vector<double>> X;
    std::vector<double> c;
  };
  mutable GasStepScratch gas_step_scratch_;
  std::vector<double> gas_x_;         ///< X of each gas point (1 elsewhere)
  std::vector<double> gas_g_;         ///< G_i of each gas point, Pa
  std::vector<std::uint8_t> vented_;  ///< gas vented (left the box); empty without gas
  std::vector<Vec3> vent_velocity_;   ///< m/s, the velocity each vented point left the box with
  Index vented_count_ = 0;
  bool vented_since_build_ = false;  ///< this rank vented a point since the last contact list build
  Index gas_rate_limited_ = 0;        ///< point-steps whose X change was limited (gas_pass.hpp)
  double time_ = 0.0;
  long steps_ = 0;
  double external_work_ = 0.0;
};

}  // namespace ballista
