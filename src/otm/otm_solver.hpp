#pragma once
// Optimal Transportation Meshfree (OTM) solver (Li, Habbal & Ortiz, IJNME 83 (2010) 1541; seed 003
// SAND2020-9716 ch. 2, Algorithm 1): nodes carry the motion, material points carry the material,
// local max-entropy shape functions (otm/lme_shape.hpp) tie them; an updated-Lagrangian explicit
// two-step scheme. The points layer (seeding, materials, loads, energies, diagnostics) is shared
// with MPM and peridynamics: this file owns the nodes, the supports and the time integration.
//
// One step (Algorithm 1, from t_k to t_k+1):
//   supports and N_a, grad N_a at the points' positions x_p^k           (lines 6-7, otm_support.hpp)
//   m_a = sum_p N_a(x_p) m_p                                            (line 8, eq. 2.13)
//   f_a = sum_p [ -V_p sigma_p grad N_a + N_a f_ext,p ]                 (line 9; axisymmetric adds the
//         hoop term -V_p sigma_tt N_a / r_p to the radial force, as the MPM solver does)
//   v_a <- v_a + (dt_k + dt_k+1)/2 f_a / m_a                            (line 11 with l_k = M_k v_k)
//   x_a <- x_a + dt_k+1 v_a
//   x_p <- sum_a N_a x_a;  dF = I + dt sum_a v_a (x) grad N_a           (lines 12-13)
//   F_p <- dF F_p;  V_p <- det(dF) V_p                                  (lines 14-16)
//   stress update through the material library with L = (dF - I) / dt.
// Momentum (ch. 2.3): the seed's own form, l_k = M_k v_k with the node velocity of the last step,
// not Li et al.'s l_a = sum_p N_a m_p v_p: nodes keep their velocity, so no PIC-like smoothing of
// the velocity field enters at each step (that form re-projects v_p = sum N v_a every step). The
// price is that momentum changes when the lumped masses change as points move among their nodes;
// the solver reports that drift (docs/validation.md).
//
// Several MPI ranks: every rank holds every node (the nodes are few beside the points' supports),
// and a share of the points (its region of a coordinate bisection of the seeding), which never
// migrate (any share works, since a point finds its nodes on its own rank). The node sums (lumped
// masses, forces, the stable step's bounds, the F-bar's averages, the projections) are folds over
// each node's points in the serial run's order: a node reached by one rank's points is folded
// there, a node reached by several ranks' points is folded by one rank from every rank's inputs
// merged in id order (otm/node_sums.hpp), so every rank updates the same nodes, bitwise the serial
// run's; the point updates, the supports and the material are each rank's own. Pinball contact
// gathers every point's ball in id order; adaptivity gathers every point where one may split (the
// children's state reads the parent's neighbours, in id order) and re-generates the nodes from
// every rank's points.
//
// Rigid walls (seed 003 ch. 4) at the grid box faces marked `wall`: `constraint` (a node that would
// cross the wall is stopped on it: zero normal displacement into it) or `penalty` (a spring
// k_a = penalty m_a omega_a^2 on the crossing distance, omega_a the node's stiffness bound).
// `fixed` faces stop nodes; `symmetry` faces and the axis hold the normal velocity at zero.
#include <memory>
#include <optional>
#include <vector>

#include "core/communicator.hpp"
#include "core/solver.hpp"
#include "materials/material.hpp"
#include "otm/otm_adaptivity.hpp"
#include "otm/otm_fbar.hpp"
#include "otm/otm_nodes.hpp"
#include "otm/otm_params.hpp"
#include "otm/node_sums.hpp"
#include "otm/otm_support.hpp"
#include "points/point_loads.hpp"
#include "points/point_set.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class OtmSolver final : public Solver {
 public:
  OtmSolver(const Scenario& scenario, std::vector<std::unique_ptr<Material>> materials, Communicator comm = {});

  const char* name() const override { return "otm"; }
  double stable_dt() override;
  void step(double dt) override;
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  FieldStore& points() override { return points_; }
  /// The nodes for the output: x, v (m/s), mass (kg; per radian in axisymmetric runs), body.
  const FieldStore* output_nodes() override;
  EnergyTotals energies() const override;
  double reporting_scale() const override;
  void begin_stage(int stage, double damping) override;
  /// The point whose term m_p G_p g_a,p is the largest in the sum of the node that sets the step
  /// (the largest Gershgorin bound, stable_dt): OTM's step is the nodes', not a point's wave speed.
  StepLimiter step_limiter() const override;
  std::string derived_constants() const override;
  /// wall_force (N, the normal reaction of the rigid walls, summed), node_count.
  std::vector<std::string> history_columns() const override;
  std::vector<double> history_values() const override;
  /// node_count, support statistics, LME iterations and fallbacks, momentum drift.
  std::vector<std::pair<std::string, double>> result_values() const override;
  /// supports (search and LME solves), assemble, node_update, point_update, material, adaptivity,
  /// stable_dt: seconds.
  std::vector<std::pair<std::string, double>> timing_values() const override;

  /// Checkpoint (otm_checkpoint.cpp): the points, the nodes, this step's and the last step's
  /// supports with their shape functions (the next step uses them; a rebuild would start the LME
  /// solves from other multipliers and differ in the last bits), the multipliers, the adaptivity
  /// state, time, step and the booked work.
  void save_state(StateArchive& archive) const override;
  void load_state(const StateArchive& archive) override;

  const otm::NodeCloud& nodes() const { return nodes_; }
  /// Adaptivity (otm_adaptivity.hpp): new nodes on the lattice over the current points, their
  /// velocities interpolated from the old nodes, linear momentum restored exactly and the
  /// kinetic-energy change booked as transfer work. adapt() decides when; public for the tests.
  void regenerate_nodes();
  const otm::Supports& supports() const { return sup_; }

 private:
  /// The nodes at the start: the vertices of the lattice cells holding each lattice-seeded body's
  /// points (otm_nodes.hpp), and the vertices of each element-seeded body's mesh; refuses what
  /// such a body does not support yet (adaptivity, shared nodes, a mesh of another spacing).
  otm::NodeCloud initial_nodes(const Scenario& sc, const OtmParams& P);
  /// Bodies whose activation time has come (rods, jets, activation_time): their points join, with
  /// nodes of their own seeded as at the start, and the nodes' velocities projected from the points.
  void activate_pending();
  /// Adaptivity: the extent tensor s0 I of points [p0, p1) and the ids the splits continue after.
  void seed_extents(Index p0, Index p1);
  /// Nodes [a0, end): lumped mass and the mass-weighted projection of the velocities of points
  /// [p0, p1), their momentum added to the initial momentum.
  void project_node_velocities(Index p0, Index p1, Index a0);
  /// on_particle_exit: delete: removes the points outside the grid box (booked as removed by the
  /// points layer) with their solver state; true if any left.
  bool remove_exits();
  /// Removes the nodes no support references (after points were deleted) and renumbers the supports.
  void drop_orphan_nodes();
  /// Supports and shape functions at the current positions; stops the run on a failed solve.
  void refresh_supports();
  /// Builds the supports; false if a point's LME solve failed (sup_.failed names it).
  bool build_current_supports();
  /// Stops the run naming the point whose LME solve failed, its support nodes and the solve's state.
  [[noreturn]] void report_failed_solve();
  /// Adaptivity after a step (otm_adaptivity.hpp): split stretched points, then re-generate the
  /// nodes if a point split, a point lost its nearby nodes, nodes crowded or a solve failed.
  void adapt();

  /// The step on this rank; step() makes the ranks agree on a failure, then drops orphan nodes.
  void step_local(double dt);
  /// Several ranks: keeps this rank's region of the seeded points (at the start).
  void keep_region_share();
  /// The influence domains of the current supports, and which ranks' points reach each node.
  void rebuild_influences();
  /// What the node sums (otm/node_sums.hpp) read: bitwise the serial run's on any rank count.
  otm::NodeFoldScope node_fold_scope() const;
  /// True if a body still waits for its activation on any rank.
  bool pending_anywhere() const;
  /// Several ranks: the support statistics of every rank's points (summary), after a step.
  void reduce_support_statistics();
  /// Several ranks, adaptivity: every rank's points in id order, if a point anywhere may split (a
  /// parent's neighbours for its children's state); else none.
  std::optional<otm::Neighbourhood> neighbourhood_for_splits();
  /// Several ranks: ids for the second children (points first_child, ...) of `parents`, numbered
  /// over every rank's parents in their ids' order as a serial run numbers them; the count of all.
  Index number_children(const std::vector<Index>& parents, Index first_child);
  /// Several ranks: every rank's points' positions, velocities, node sets and (if asked) masses, in
  /// id order.
  void points_in_id_order(std::vector<Vec3>& x, std::vector<Vec3>& v, std::vector<std::int64_t>& group,
                          std::vector<double>* mass = nullptr) const;
  /// omega2_ per node (stable_dt; c the largest signal speed): from the rows of M^-1 K
  /// (otm.step_bound: gershgorin) or of M^-1/2 K M^-1/2 (symmetric).
  void row_sum_node_bounds(double c);
  void symmetric_node_bounds(double c);
  /// Lumped masses and residual forces from the current supports.
  void assemble();
  /// Each node's lumped mass from the current supports (the fold assemble() also makes).
  std::vector<double> lumped_masses() const;
  /// Nodes whose lumped mass is a negligible share of any point's (outside the body, reached only
  /// by the tails of the shape functions), with the velocity the points give them: the
  /// mass-weighted projection of Li, Habbal & Ortiz (2010). Empty if there are none.
  std::vector<std::pair<Index, Vec3>> light_nodes() const;
  /// Velocity constraints of the box faces on the nodes after the update (fixed, symmetry, and
  /// constraint walls, whose normal reaction goes to wall_force_ for the history).
  void apply_face_conditions(double dt);
  /// Pinball contact between the bodies (otm.contact: pinball; otm_contact.hpp): the force on each
  /// node from its points' contact forces; sets contact_pairs_.
  std::vector<Vec3> contact_node_forces();

  Scenario scenario_;
  Communicator comm_;
  PointSet pts_;
  FieldStore& points_;
  PointLoads loads_;
  otm::NodeCloud nodes_;
  FieldStore node_out_;           ///< the nodes as written (output_nodes)
  otm::SupportOptions sopt_;
  otm::Supports sup_, prev_sup_;  ///< this step's supports and the last step's (retries)
  otm::SupportCandidates candidates_;  ///< each point's nodes within a margin (not checkpointed: searched again)
  std::vector<Vec3> v_start_;     ///< node velocities at the start of the step (wall booking)
  std::vector<double> omega2_;    ///< 1/s^2, each node's Gershgorin bound on omega^2 (stable_dt; penalty walls)
  std::vector<double> scale_;     ///< support radius scale per point (largest principal stretch)
  std::vector<Vec3> lambda_;   ///< LME multiplier per point (warm start)
  otm::AdaptivityOptions adapt_;
  otm::SplitStateSpec split_state_;  ///< adaptivity: what a split point's children interpolate
  std::vector<Mat3> Fr_;       ///< adaptivity: each point's deformation since the nodes were last re-generated
  std::vector<double> spacing_;  ///< m, seeded point spacing per body (cell_size / particles_per_cell)
  bool fbar_on_ = false;  ///< otm.anti_locking: fbar
  bool symmetric_bound_ = false;  ///< otm.step_bound: symmetric
  otm::NodalFBar fbar_;
  std::int64_t next_id_ = 0;     ///< id of the next point made by a split
  std::vector<char> interpolated_;  ///< last re-generation: node velocity interpolated (1) or projected (0)
  Index splits_ = 0, regenerations_ = 0;
  std::int64_t carried_node_steps_ = 0;  ///< light nodes carried by the points, summed over the steps
  double remap_work_ = 0.0;      ///< J per radian/metre: kinetic-energy change of the node re-generations
                                 ///< and of the light nodes carried by the points (light_nodes)
  int dim_ = 3;                ///< axes of the motion: 3, or 2 (plane strain, axisymmetric)
  bool axisym_ = false;
  bool penalty_ = false;       ///< rigid walls by penalty instead of the constraint
  double penalty_factor_ = 1.0;
  bool delete_exits_ = false;  ///< simulation.on_particle_exit: delete
  bool contact_ = false;       ///< pinball contact between bodies (otm.contact)
  double contact_penalty_ = 1.0;
  Index contact_pairs_ = 0;    ///< pairs of points in contact at the last step
  double damping_ = 0.0;       ///< 1/s (stages)
  double dt_prev_ = 0.0;       ///< s, the previous step (0 before the first)
  double time_ = 0.0;
  long steps_ = 0;
  double external_work_ = 0.0, damping_work_ = 0.0, wall_work_ = 0.0, contact_work_ = 0.0;
  double wall_force_ = 0.0;    ///< N, last step's normal wall reaction
  Vec3 momentum0_;             ///< initial nodal momentum (per radian / per metre)
  otm::Influences inf_;          ///< influence domains of sup_ (node-wise gathers)
  otm::NodeSharing sharing_;     ///< several ranks: which ranks' points reach each node
  /// s, wall time per phase of the step (timing_values; bench/otm_taylor_bench).
  struct PhaseSeconds {
    double supports = 0, assemble = 0, nodes = 0, points = 0, material = 0, adapt = 0, stable_dt = 0;
  } seconds_;
  double mean_support_ = 0.0;
  int max_support_ = 0, max_iterations_ = 0;
  double max_condition_ = 0.0;
  Index fallbacks_ = 0, retries_ = 0;
  /// The statistics above over every rank (summary; this rank's own on one rank).
  struct SupportTotals {
    double mean = 0.0, max_condition = 0.0;
    int max_size = 0, max_iterations = 0;
    Index fallbacks = 0, retries = 0;
  } support_totals_;
  Index seeded_points_ = 0;  ///< every rank's points at the start (derived_constants)
  bool removed_ = false;     ///< points left the box this step: orphan nodes go after it
};

}  // namespace ballista
