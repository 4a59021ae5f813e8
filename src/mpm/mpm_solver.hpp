#pragma once
// Explicit Material Point Method (Sulsky, Chen & Schreyer, CMAME 118 (1994) 179; update-stress-
// last and modified-USL as in Nairn, CMES 4 (2003) 649 and Buzzi et al. 2008), the solver of the
// thesis seed 000 (ch. 5-6, run there in Uintah). By default one velocity field on the grid for all
// bodies (no-slip, no separation); with `contact.model: friction` each body or group of bodies has
// its own field and frictional contact where they meet (mpm/grid_contact.hpp).
#include <atomic>
#include <memory>
#include <vector>

#include "core/communicator.hpp"
#include "core/solver.hpp"
#include "materials/material.hpp"
#include "mpm/active_blocks.hpp"
#include "mpm/anti_locking.hpp"
#include "mpm/bulk_viscosity.hpp"
#include "mpm/grid_exchange.hpp"
#include "mpm/grid_geometry.hpp"
#include "mpm/p2g_part.hpp"
#include "mpm/patch_constraints.hpp"
#include "mpm/shape_functions.hpp"
#include "points/point_loads.hpp"
#include "points/point_set.hpp"
#include "points/rcb_partition.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Grid arrays of one block (nodal mass, momentum/velocity, force), one set per velocity field,
/// stored field after field (node I of field f at f * node_count + I).
struct GridData {
  GridGeometry geom;
  int fields = 1;
  std::vector<double> mass;      ///< kg
  std::vector<Vec3> velocity;    ///< m/s: momentum during P2G, then velocity at t_n
  std::vector<Vec3> force;       ///< N: internal + external during P2G
  std::vector<Vec3> velocity_new;///< m/s at t_{n+1} after boundary conditions
  std::vector<Vec3> accel;       ///< m/s^2 over the step (after boundary conditions)
  std::vector<Vec3> grad;        ///< sum_p w_p grad N_I, outward from the field's material (several fields only; w_p and units: FieldGrid::grad)
  std::vector<Vec3> impulse;     ///< m/s: the step's contact corrections per node (several fields only)
  std::vector<Vec3> friction_impulse;  ///< m/s: their tangential (Coulomb) parts
  /// sum_p N_I V_p per field and node, in the particle volumes' unit (contact's gap check only:
  /// contact.min_volume_fraction > 0 with several fields; empty otherwise)
  std::vector<double> volume;
  bool with_volume = false;  ///< whether resize allocates `volume`
  void resize(Index n) {
    if (fields > 1) grad.assign(n, Vec3{});
    if (with_volume) volume.assign(n, 0.0);
    mass.assign(n, 0.0);
    velocity.assign(n, Vec3{});
    force.assign(n, Vec3{});
    velocity_new.assign(n, Vec3{});
    accel.assign(n, Vec3{});
  }
};

class MpmSolver final : public Solver {
 public:
  MpmSolver(const Scenario& scenario, std::vector<std::unique_ptr<Material>> materials,
            Communicator comm = {});

  const char* name() const override { return "mpm"; }
  double stable_dt() override;
  void step(double dt) override;
  double land_step(double dt) const override;  ///< multi-rate: on pending activations (mpm_multirate.cpp)
  double time() const override { return time_; }
  long steps() const override { return steps_; }
  FieldStore& points() override { return points_; }
  Index pending_points() const override { return pts_.pending(); }
  EnergyTotals energies() const override;
  double reporting_scale() const override;
  void begin_stage(int stage, double damping) override;
  StepLimiter step_limiter() const override;
  /// Indenter reactions of the loads (PointLoads::history_columns).
  std::vector<std::string> history_columns() const override { return PointLoads::history_columns(scenario_); }
  std::vector<double> history_values() const override;

  /// Checkpoint: the particles (points layer), time, step, stage damping and the booked work
  /// terms. The grid is rebuilt from the particles every step, so it holds no state.
  void save_state(StateArchive& archive) const override;
  void load_state(const StateArchive& archive) override;

  const GridData& grid() const { return grid_; }
  /// Several ranks: what the decomposition did (summary.json solver_results).
  std::vector<std::pair<std::string, double>> result_values() const override;
  const std::vector<std::unique_ptr<Material>>& materials() const { return pts_.materials(); }

 private:
  void activate_pending();
  /// Several ranks: particles that left this rank's region go to its owner; a repartition when the
  /// largest rank holds more than (1 + mpm.rebalance_imbalance) times the mean (collective).
  void redistribute();
  /// Several ranks: new cuts from where the particles are, and the particles moved to them
  /// (collective); returns how many this rank sent and received.
  Index cut_and_migrate();
  void step_local(double dt);
  void sort_by_cell();
  /// The slabs of the points [begin, end) (end < 0: to the last), which the P2G passes scatter.
  void build_slabs(Index begin = 0, Index end = -1);
  template <int Dim, ShapeKind K, bool G> void step_impl(double dt);
  /// P2G of the sums of `part` (p2g_part.hpp) from the points of the last build_slabs; the momenta
  /// m_p v_p are those of `v_source` if given. [begin, end) selects the surface tractions mapped
  /// with them (their points' range).
  template <int Dim, ShapeKind K, bool G>
  void particles_to_grid(P2gPart part, const Vec3* v_source = nullptr, Index begin = 0, Index end = -1);
  /// XPIC(m): the grid velocity the PIC share of the update reads, into xpic_.target.
  template <int Dim, ShapeKind K, bool G> void xpic_velocity(double dt);
  /// G2P of the points [begin, end) (end < 0: to the last).
  template <int Dim, ShapeKind K, bool G, bool Usavg> void grid_to_particles(double dt, Index begin = 0, Index end = -1);
  template <int Dim, ShapeKind K, bool G>
  void velocity_gradient_from_grid(double dt, bool move, Index begin = 0, Index end = -1);
  template <int Dim, ShapeKind K, bool G> void first_half_stress_update(double dt);
  /// USAVG's first half on the grid: v0 from the momenta (into accel), the constrained v_n into
  /// usavg_start_ and velocity_new, the constraints' impulses booked.
  void usavg_start_velocity();
  /// ... and on the points [begin, end): L from v_n, half the stress update over dt, its q.
  template <int Dim, ShapeKind K, bool G> void first_half_points(double dt, Index begin, Index end);
  void velocity_from_momentum();  // velocity_new = momentum / mass at the active nodes
  double grid_kinetic_energy_change(double dt);  // over the step, after update_grid
  void finish_point(Index p, const Mat3& l, const Vec3& disp, double dt, std::atomic<Index>& bad,
                    std::atomic<Index>& out);
  void bind_fields();
  /// The point fields the F-bar reads and rewrites, with each point's material (averaged per material).
  FBarPoints fbar_points();
  /// On several ranks: the F-bar's per-(cell, material) sums over the ranks sharing a cell.
  FBarSlotSum fbar_across_ranks();
  void update_grid(double dt);
  /// One velocity change a face or axis condition made at a node (field-major node index).
  struct BoundaryImpulse {
    Index node;
    int axis;
    double change;  ///< m/s
  };
  /// Imposes the face and axis conditions on every field's nodal velocities; records each change
  /// in `impulses` if given.
  void apply_velocity_bcs(Vec3* vel, std::vector<BoundaryImpulse>* impulses = nullptr);
  /// Books the work of this step's contact and boundary impulses with the step's midpoint velocity.
  void book_impulses(const Vec3* v_start, const Vec3* v_end);
  std::vector<Vec3> usavg_start_;  ///< USAVG: the constrained grid velocity v_n of the first half, m/s
  std::vector<BoundaryImpulse> boundary_impulses_;  ///< this step's, for book_impulses
  /// Cubic B-spline at symmetry faces and the axis: folds what the stencils put on the ghost nodes
  /// beyond a mirror face onto their mirror images inside (normal component negated) and leaves
  /// the ghosts empty; the arrays of the pass's part (p2g_part.hpp).
  void fold_mirror_faces(P2gPart part);
  /// ... and sets the ghost nodes of every field to the mirror image of the inside values.
  void fill_mirror_ghosts(Vec3* v);
  /// Patches (grid.patches; mpm_patches.cpp): the refusals, the cell-edge table and the coarser
  /// levels' grids, set up once.
  void setup_patches(const Scenario& sc);
  /// Patches with an end (grid.patches[].until): from the first step that starts at or after it,
  /// the grid without them (mpm_patches.cpp). Called before each step's stable step.
  void drop_patches_if_due();
  /// ... and the patched grid again for a state loaded from before their end (load_state).
  void restore_patches_if_due();
  /// The grid of `sc` (its layout, arrays and blocks), without patch tables (setup_patches adds them).
  void rebuild_grid(const Scenario& sc);
  bool patches_dropped_ = false;
  /// Patches: moves the hanging nodes' sums of the pass's part to their masters
  /// (mpm/patch_constraints.hpp) ...
  void fold_patch_nodes(P2gPart part);
  /// ... and sets every field's hanging nodes of `v` from their masters.
  void fill_patch_nodes(Vec3* v) const;
  PatchConstraints patch_;                      ///< the hanging nodes (empty without patches)
  /// Patches: level k's grid (the splits of the patches of depth <= k only; ghost layers included)
  /// and each of its nodes' index in the grid (-1: a ghost node the grid does not have), for k
  /// below the deepest. A point whose uGIMP domain is clear of every patch deeper than k takes its
  /// weights on level k's cells, the coarsest such, as on a grid without those patches: on cells
  /// split further its domain would be clamped to half a split cell (gimp_1d), and such domains,
  /// which no longer tile the body, leave a static imbalance beside a patch.
  std::vector<GridGeometry> level_geom_;
  std::vector<std::vector<Index>> level_to_grid_;
  std::vector<char> stencil_level_;  ///< per point, this step: the level its weights are on
  /// The domain [x - half, x + half] clear of every patch of depth >= `depth` (and,
  /// axisymmetric, of the axis).
  bool clear_of_patches(const Vec3& x, const Vec3& half, int depth) const;
  std::shared_ptr<const GridAxes> patch_axes_;  ///< the grid's axes and patches (null without patches)
  /// The shortest edge of the cell a point at x lies in (graded grids; a patch's or, outside the
  /// patches, the coarse cell its hanging nodes follow): the length its signal crosses in a step.
  double cell_edge(const Vec3& x) const;
  /// With patches the step is the fine cells', and the PIC share damps once per step (its rate
  /// (1 - flip) / dt): a point in coarser cells takes (1 - flip) l_step / l_p per step, the rate
  /// its own cells' step would give, so that the fine cells elsewhere do not damp it more than the
  /// coarse grid would (grid_to_particles; each substep's for a multi-rate step's slow points).
  bool pic_by_cell() const { return patch_axes_ && flip_ < 1.0 && step_cell_ > 0.0; }
  double pic_share_by_cell(const Vec3& x) const { return (1.0 - flip_) * std::min(1.0, step_cell_ / cell_edge(x)); }
  /// Patches: each of the grid's cells' shortest edge as its region sees it (the cell of the patch
  /// or coarse grid holding it: GridAxes::effective_cell_size), x fastest; cell_edge looks it up.
  std::vector<double> patch_cell_edge_;
  /// Multi-field contact on `vel` (every field); with `book` its impulses go to grid_.impulse and
  /// grid_.friction_impulse for book_impulses.
  void apply_contact(Vec3* vel, bool book);
  /// Offset of point p's velocity field in the grid arrays.
  Index field_offset(Index p) const {
    return grid_.fields > 1 ? scenario_.contact.body_field[body_[p]] * grid_.geom.node_count() : 0;
  }
  void handle_exits();
  [[noreturn]] void fail(Index p, const std::string& what) const;
  int stencil_reach_now() const;

  /// Node layout of the grid block: geometry, physical box and its node index range per axis.
  struct GridLayout {
    GridGeometry geom;
    Vec3 box_lower, box_upper;      ///< physical grid box (without ghost layers), m
    int box_first[3], box_last[3];  ///< node index range of the physical box per axis
  };
  static GridLayout layout_grid(const Scenario& sc, int ghost);
  static GridLayout layout_graded_grid(const Scenario& sc, int ghost);
  /// Graded grids: the stable step from each point's own cell, and those cells' shortest edges.
  double graded_stable_dt();
  double uniform_stable_dt();
  /// wave_scratch_ = each point's dilatational wave speed, 0 for points failed to zero stress.
  void fill_wave_speeds();
  void update_cell_lengths(Index begin = 0, Index end = -1);
  std::vector<double> cell_length_;  ///< m, per point (graded grids)
  /// Patches: the cell of the point that set this step's stable step, m (0: not known).
  double step_cell_ = 0.0;
  double viscous_rate_ = 0.0;        ///< graded grids: the last viscous pass's max signal speed / cell, 1/s
  static constexpr int kGhostLayers = 3;  ///< ghost node layers beyond the box on each side

  Scenario scenario_;
  Communicator comm_;
  GridLayout layout_;
  PointSet pts_;        ///< the particles, their materials and their bookkeeping (points layer)
  FieldStore& points_;  ///< pts_.store()
  PointLoads loads_;    ///< external forces of this step
  Dimension dimension_;
  int dim_;
  ShapeKind shape_;
  /// Cubic B-spline only: faces with the boundary-modified basis (fixed and wall faces; Steffen
  /// et al. 2008) and faces continued by the mirror image (symmetry faces and the axis).
  SplineFaces spline_faces_;
  struct MirrorFace {
    int axis;   ///< normal axis
    int node;   ///< node index of the face on that axis
    int side;   ///< -1: ghosts below the face (x_min), +1: above it (x_max)
  };
  std::vector<MirrorFace> mirror_faces_;
  bool musl_;
  bool usavg_ = false;  // update: usavg (first_half_stress_update)
  BulkViscosity bulk_viscosity_;  ///< mpm.bulk_viscosity_linear / _quadratic / _sound_speed
  double viscous_speed_ = 0.0;    ///< the last pass's signal speed with q, m/s (stable_dt)
  std::vector<double> wave_scratch_;
  std::vector<double> reference_wave_scratch_;  ///< mpm.bulk_viscosity_sound_speed: reference
  /// After a stress update over dt: books the viscous heating, sets q (apply_bulk_viscosity) of
  /// the points [begin, end).
  void bulk_viscosity_pass(double dt, bool book_new, Index begin = 0, Index end = -1);
  double flip_;
  int xpic_order_ = 1;  ///< mpm.xpic_order (1: the PIC share is plain PIC)
  /// XPIC runs only where it acts: order > 1 and a PIC share (flip < 1).
  bool xpic_active() const { return xpic_order_ > 1 && flip_ < 1.0; }
  struct XpicScratch {
    std::vector<Vec3> prev, target;  ///< per node of every field: C(m,k) A^(k-1) v, then v* + dt a
    std::vector<Vec3> at_points;     ///< per point: the interpolated prev
  } xpic_;
  int sort_every_ = 20;  ///< steps between particle sorts (0 = never)
  double damping_;
  AntiLocking anti_locking_ = AntiLocking::None;  ///< mpm.anti_locking
  CellFBar fbar_;                                 ///< F-bar scratch (anti_locking: fbar)
  GridData grid_;
  ActiveBlocks blocks_;  ///< the grid blocks particles reach this step (only they are zeroed and updated)
  GridExchange exchange_;   ///< several ranks: the blocks shared with other ranks and their sums
  RcbPartition partition_;  ///< several ranks: which rank owns which region (Zoltan RCB)
  double rebalance_ = 0.1;  ///< mpm.rebalance_imbalance
  // Decomposition statistics (several ranks): repartitions, particles migrated, halo per step.
  long repartitions_ = 0;
  double imbalance_after_partition_ = 0.0;  ///< what the last repartition achieved
  bool activated_this_step_ = false;  ///< several ranks: some rank activated pending particles this step
  double neighbour_sum_ = 0.0, neighbour_plans_ = 0.0;  ///< statistics of the neighbour exchange
  double migrated_ = 0.0, halo_bytes_ = 0.0, halo_messages_ = 0.0, halo_steps_ = 0.0, max_imbalance_ = 0.0;
  int reach_ = 1;        ///< the shape function's reach this step, nodes (build_slabs)
  /// Marks this step's active blocks (particles and traction points) and clears the released ones.
  void mark_active_blocks();
  /// f(i) for every node i of the active blocks in every velocity field.
  template <class F>
  void for_each_active_node(F&& f) const {
    for (int k = 0; k < grid_.fields; ++k) blocks_.for_each_node(k * grid_.geom.node_count(), f);
  }
  static constexpr double kTinyMass = 1e-200;  ///< nodes lighter than this carry no material
  int ghost_ = kGhostLayers;    ///< ghost node layers beyond the box on each side
  std::vector<Vec3> displacement_;  ///< MUSL: dt * grid velocity at each point this step, m
  /// GIMP: each point's windows (GimpWindows), computed by the step's first mapping and read by
  /// its later passes: every pass of a step maps from the positions the step began with, and
  /// the half-lengths do not change within it. Valid while `windows_current_`.
  std::vector<GimpWindows<2>> windows2_;
  std::vector<GimpWindows<3>> windows3_;
  bool windows_current_ = false;
  template <int Dim>
  std::vector<GimpWindows<Dim>>& gimp_windows_of_points() {
    if constexpr (Dim == 2) return windows2_;
    else return windows3_;
  }
  /// Point p's stencil for this step (from its kept GIMP windows once they are current).
  template <int Dim, ShapeKind K, bool G>
  void point_stencil(Index p, const Vec3& x, const Vec3& half, Stencil<Dim>& st);
  /// The same for a uGIMP point on a grid with patches (mpm_patches.cpp): its weights on the
  /// coarsest nesting level its domain allows (level_geom_).
  template <int Dim>
  void patch_point_stencil(Index p, const Vec3& x, const Vec3& half, GimpWindows<Dim>& w, Stencil<Dim>& st);
  Index first_bad_ = 0, first_out_ = 0;  ///< lowest inverted / escaped point of the step (or n)
  // Field pointers bound at the start of each step (valid until points are reordered).
  Vec3* x_ = nullptr;
  Mat3* F_ = nullptr;
  Mat3* L_ = nullptr;
  double* vol_ = nullptr;
  const double* vol0_ = nullptr;
  const std::int64_t* body_ = nullptr;
  std::vector<Index> slab_start_, slab_points_;      ///< CSR lists of point indices per slab
  std::vector<int> slab_of_point_;                   ///< scratch: slab of each point
  std::vector<Index> slab_fill_;                     ///< scratch: fill cursor per slab
  std::vector<Index> sort_key_, sort_start_, sort_order_;  ///< scratch of sort_by_cell
  int slab_axis_ = 2, slab_width_ = 2;
  double time_ = 0.0;
  long steps_ = 0;
  // Energy bookkeeping, per-point sums (not yet scaled; EnergyTotals names each term).
  double external_work_ = 0.0;
  double damping_work_ = 0.0;
  double contact_work_ = 0.0, friction_work_ = 0.0;
  double transfer_work_ = 0.0;
  double boundary_work_ = 0.0;
  double viscous_work_ = 0.0;
  // Multi-rate stepping (mpm.multirate; mpm_multirate.cpp).
  int multirate_max_ = 1;     ///< largest substeps per step (1: one step for every point)
  double fine_dt_ = 0.0;      ///< the fastest point's stable step at the last stable_dt, s
  std::vector<double> point_step_;  ///< each point's own stable step at the last stable_dt, s
  /// The slow points' share of the grid, held over the step's substeps: their mass, contact
  /// normal and volume sums (as each of USAVG's two passes maps them), their forces; the velocity they see (u), at the start (u0), the
  /// displacement it makes (disp), and the first half's constrained velocity (vn0).
  struct MultirateGrid {
    std::vector<double> mass, volume, volume_forces;
    std::vector<Vec3> grad, force, u, u0, disp, vn0;
    std::vector<Vec3> fext;                      ///< the slow points' point loads at the step's start
    std::vector<PointLoads::SurfaceForce> surface;  ///< and their surface tractions
    std::vector<Index> slab_start, slab_points;     ///< their slabs (build_slabs), for their forces' P2G
  } multirate_;
  /// Over the steps that took substeps: their count and their substeps' (fast), the point updates
  /// made by fast and slow points, and those every point at every substep would have made.
  struct MultirateTally {
    double steps = 0.0, substeps = 0.0, fast_point_steps = 0.0, slow_point_steps = 0.0;
    double single_rate_point_steps = 0.0;
  } multirate_tally_;
  /// stable_dt with multi-rate stepping: the step of the slow points (a power-of-two multiple of
  /// the fastest point's, chosen for the fewest point updates), point_step_ and fine_dt_ set.
  double multirate_stable_dt(double single_dt);
  /// step_cell_: the cell of the point with the highest (c + |v|) / l, points with skip[p] set
  /// left out (skip empty: none).
  void set_step_cell(const std::vector<char>& skip);
  /// The points at rest (v = 0, stress-free, unloaded) that no moving point can reach within a
  /// step of multirate_max_ substeps: 1 for each (multirate_idle.cpp), or empty if there are none.
  std::vector<char> idle_points() const;
  /// The ids of the points idle_points() left idle at the last stable_dt, ascending.
  std::vector<std::int64_t> idle_ids_;
  /// Stops the run if a point left idle for the step ended it moved or stressed.
  void check_idle_points_rest() const;
  /// Puts the points that step at the fine step first (returns their count): those whose own
  /// step is shorter than dt, and every point within kMultirateBuffer cells of one.
  Index partition_by_rate(double dt);
  template <int Dim, ShapeKind K, bool G> void step_multirate(double dt, int substeps);
  /// The step: multi-rate when the fastest points need substeps of it, else step_impl.
  template <int Dim, ShapeKind K, bool G> void step_any(double dt);
  /// The slow points' update at the end of the step, from MultirateGrid.
  template <int Dim, ShapeKind K, bool G>
  void slow_grid_to_particles(double dt, int substeps, Index begin, Index end);
  // Last: placed among the members the step reads every time, this scratch shifted their layout
  // and cost the 3D block-impact bench ~3 % (docs/performance.md).
  std::vector<double> force_pressure_;  ///< per point: isotropic stress the F-bar's forces take off sigma, Pa
  std::atomic<std::int64_t> frozen_discarded_{0};  ///< this step's discarded increments (finish_point)
};

}  // namespace ballista
