#pragma once
// The validated, fully resolved description of a run: what the deck reader produces and the
// solvers, probes and writers consume. Every length is in m, time in s, velocity in m/s,
// pressure and moduli in Pa, density in kg/m^3 (docs/deck.md).
#include <array>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/tensor.hpp"
#include "materials/material.hpp"

namespace ballista {

enum class Dimension { ThreeD, PlaneStrain, Axisymmetric };
/// Boundary condition on one face of the grid box.
enum class FaceBC {
  Free,      ///< nothing imposed
  Fixed,     ///< all velocity components zero
  Symmetry,  ///< normal velocity zero (roller)
  Wall,      ///< rigid frictionless wall: normal velocity may not point into the wall
};

/// Where a value came from in the deck (for error messages raised after parsing).
struct DeckMark {
  std::string file;
  std::string key_path;
  int line = 0;
  int column = 0;
};

/// Piecewise-linear function of time, held constant beyond its first and last points.
struct LoadCurve {
  std::vector<double> t;  ///< s, strictly increasing
  std::vector<double> v;  ///< scale factor (dimensionless)
  double at(double time) const;
};

struct SimulationSpec {
  std::string solver = "mpm";       ///< a registered solver (points/solver_registry.hpp)
  Dimension dimension = Dimension::ThreeD;
  /// `dimension: plane_stress` (peridynamics): a 2D run like plane_strain (points in the x-y plane,
  /// per unit thickness) whose in-plane constants are those of plane stress.
  bool plane_stress = false;
  double end_time = 0.0;            ///< s
  double cfl = 0.3;                 ///< Courant number (0, 1]
  double max_dt = 0.0;              ///< s; 0 = no cap
  long max_steps = 0;               ///< 0 = unlimited: the run ends (completed) after this many steps
  /// A run whose estimated step count (simulated time / first stable step) exceeds this is refused
  /// before it starts, and one that reaches it stops with a diagnostic (a collapsed step).
  long step_limit = 10'000'000;
  double damping = 0.0;             ///< 1/s; grid acceleration a - c v (dynamic relaxation)
  double energy_drift_limit = 0.0;  ///< stop if |E_total - E0| / max(E0, E_scale) exceeds this; 0 = off
  std::string on_particle_exit = "stop";  ///< "stop" or "delete"
  int threads = 0;                  ///< 0 = OpenMP default
};

/// A band of finer cells along one axis of the grid (grid.refine): cells of at most `cell_size`
/// from `from` to `to`, graded into the coarse cells around it (geometry/grid_axes.hpp).
struct RefineZone {
  int axis = 0;            ///< 0 x, 1 y, 2 z
  double from = 0.0;       ///< m
  double to = 0.0;         ///< m
  double cell_size = 0.0;  ///< m
  DeckMark mark;
};

/// A box of finer cells (grid.patches): each of the grid's cells inside it is split into equal
/// cells of at most `cell_size`, and outside it the grid keeps its own cells, the split lines'
/// nodes there being tied to the coarse cells' (hanging nodes; mpm/patch_constraints.hpp).
struct GridPatch {
  Vec3 lower;              ///< m, on nodes of the grid without patches
  Vec3 upper;              ///< m
  double cell_size = 0.0;  ///< m
  /// s after the main stage begins: from the first step that starts then, the grid is the one
  /// without the patches (every patch shares it; infinite: kept for the whole run).
  double until = std::numeric_limits<double>::infinity();
  DeckMark mark;
};

struct GridSpec {
  Vec3 lower;               ///< m; z ignored in 2D
  Vec3 upper;               ///< m
  double cell_size = 0.0;   ///< m: the cubic cells of a uniform grid; the largest cells of a graded one
  /// Bands of finer cells: a rectilinear (graded) grid whose cells along each axis are the zones'
  /// in the zones and grow by at most `grading` per cell to cell_size between them. Empty: uniform.
  std::vector<RefineZone> refine;
  double grading = 1.2;     ///< largest ratio of neighbouring cell sizes of a graded grid
  DeckMark refine_mark;
  /// Boxes of finer cells with hanging nodes around them; empty: none.
  std::vector<GridPatch> patches;
  /// Non-uniform node coordinates along some axis (bands or patches): the graded path.
  bool graded() const { return !refine.empty() || !patches.empty(); }
  /// Per face: x_min, x_max, y_min, y_max, z_min, z_max.
  std::array<FaceBC, 6> faces{FaceBC::Free, FaceBC::Free, FaceBC::Free,
                              FaceBC::Free, FaceBC::Free, FaceBC::Free};
  /// x inside the box, faces included (all three coordinates: 2D points have z = 0 inside it).
  bool contains(const Vec3& x) const {
    for (int d = 0; d < 3; ++d)
      if (!(x[d] >= lower[d] && x[d] <= upper[d])) return false;
    return true;
  }
};

struct MaterialSpec {
  std::string name;
  std::string model;
  ParamValues params;  ///< every ParamSpec of the model, defaults filled
  DeckMark mark;
  std::map<std::string, DeckMark> param_marks;
};

/// Solid shapes. In 2D only x and y are used (axisymmetric: x = r, y = axial z).
/// A solid given by a closed surface read from a file (geometry/surface_solid.hpp implements
/// it; the deck reader builds it): point membership and bounds, already in metres.
class SolidShape {
 public:
  virtual ~SolidShape() = default;
  virtual bool contains(const Vec3& x) const = 0;
  virtual Vec3 lower() const = 0;
  virtual Vec3 upper() const = 0;
};

struct ShapeSpec {
  std::string type;       ///< box | cylinder | sphere | tube | cone | liner | revolution | surface | mesh
  Vec3 lower, upper;      ///< box corners, m
  Vec3 center;            ///< sphere centre / cylinder and tube base centre, m
  int axis = 2;           ///< cylinder/tube axis: 0 x, 1 y, 2 z
  double radius = 0.0;    ///< m (outer radius of a tube; in 2D a cylinder across its axis is a disk)
  double inner_radius = 0.0;  ///< tube inner radius, m
  double length = 0.0;    ///< cylinder/tube length along axis, m
  /// cone, liner, revolution: the section in the half plane (r, a) of the distance from the axis
  /// and along it from `center` (m; geometry/revolution.hpp). The cone and the liner are made
  /// from their own keys, kept below for the record.
  std::vector<std::array<double, 2>> outline;
  double top_radius = 0.0;  ///< cone: radius at center + length along the axis, m
  double angle = 0.0;       ///< liner: full apex angle, degrees
  double thickness = 0.0;   ///< liner: wall thickness normal to the wall, m
  std::string file;       ///< surface: the surface file read (absolute path)
  std::shared_ptr<const SolidShape> solid;  ///< surface: the solid it bounds (lower/upper: its box)
};

/// One piece of a body with its own shape, velocity and activation (a segment of a segmented
/// rod or of the discrete shaped-charge jet of thesis seed 000 §5.1, Fig. 5.2).
struct SegmentSpec {
  ShapeSpec shape;               ///< a cylinder along the penetrator's axis
  Vec3 velocity;                 ///< m/s
  double activation_time = 0.0;  ///< s after the start of the body's activation stage
};

/// Geometry of a rod or jet body (`rod:` / `jet:` in the deck).
struct PenetratorSpec {
  std::string kind;      ///< "rod" or "jet"; empty for a plain `shape:` body
  int axis = 1;          ///< axis of flight
  double direction = -1; ///< +1: flies towards +axis, -1: towards -axis
  Vec3 nose;             ///< m: centre of the leading face (rod) or of the insertion plane (jet)
  double length = 0.0;   ///< m: total length of penetrator material (sum of segment lengths)
  double diameter = 0.0; ///< m: rod diameter; jet: mass-weighted mean segment diameter
  double speed = 0.0;    ///< m/s: speed of the leading segment
};

struct BodySpec {
  std::string name;
  std::string material;
  ShapeSpec shape;               ///< plain bodies; for rods and jets the first segment's shape
  int particles_per_cell = 2;    ///< per direction
  /// How the points are placed: `lattice` (particles_per_cell per grid cell inside the shape),
  /// `cut_lattice` (the same, the sub-cells the surface cuts keeping the part inside:
  /// geometry/cut_lattice.hpp) or `elements` (a mesh shape's elements: one point per tetrahedron at
  /// its centroid, with its volume; geometry/seeding.hpp seed_elements).
  std::string seeding = "lattice";
  /// Peridynamics: this body's lattice spacing, m (0: grid.cell_size). Only explosive bodies (the
  /// products, a peridynamic gas) may be coarser than the case they drive (docs/deck.md).
  double point_spacing = 0.0;
  Vec3 velocity;                 ///< initial velocity, m/s
  /// Initial radial speed away from the shape's axis (cylinders and tubes), added to velocity, m/s:
  /// an expanding ring or cylinder (fragmentation, seed 001).
  double radial_speed = 0.0;
  /// Shapes cut out of the body (notches, holes, slots): no point is seeded inside any of them.
  std::vector<ShapeSpec> cutouts;
  double activation_time = 0.0;  ///< s after the start of the activation stage; inert and invisible before
  int activation_stage = 0;      ///< index of the stage that starts the activation clock (stages.size() = main)
  std::string initial_state = "none";  ///< none or a registered initial state (points/initial_state_registry.hpp)
  /// Principal stresses (Pa, tension positive; along x, y, z, or r, z, theta) the body starts in,
  /// with the deformation and state its material reaches them with (points/prestress.hpp): set by a
  /// `confinement` load with `prestress: true`, whose full traction then holds it from t = 0.
  std::optional<Vec3> prestress;
  PenetratorSpec penetrator;     ///< rod / jet description (kind empty for plain bodies)
  std::vector<SegmentSpec> segments;  ///< rods and jets: the pieces seeded (empty for plain bodies)
  DeckMark mark;
};

/// One entry of `loads`: a registered load kind (points/load_registry.hpp) and the values its
/// reader took from the deck (the kind's file says which, with units).
struct LoadSpec {
  std::string type;      ///< a registered load kind (gravity is read as a body_force, confinement as pressures)
  std::string body;      ///< body name ("" = every body, where the kind allows it)
  ParamValues params;    ///< numbers (SI units); words in params.choices
  std::map<std::string, Vec3> vectors;  ///< vectors (SI units)
  LoadCurve curve;       ///< scale factor of time (default: 1)
  DeckMark mark;
};

/// A pre-crack or notch (peridynamics): every bond of `body` (all bodies if empty) whose two ends,
/// projected on the x-y plane, lie on either side of the segment from..to is broken before the run
/// (a crack through the whole thickness in 3D).
struct CrackSpec {
  std::string body;
  Vec3 from, to;  ///< m (z ignored)
  DeckMark mark;
};

/// One entry of `probes`: a registered probe kind (points/probe_registry.hpp) and the values of
/// the parameters that kind declares.
struct ProbeSpec {
  std::string name;
  std::string type;    ///< a registered probe kind
  ParamValues params;  ///< numbers (an axis as 0, 1, 2); words (body, field) in params.choices
  std::map<std::string, Vec3> vectors;  ///< vector parameters (max_radius: center), m
  DeckMark mark;
};

struct OutputSpec {
  double interval = 0.0;             ///< s between HDF5 outputs; 0 = only first and last
  std::vector<std::string> fields;   ///< field names to write; empty = all
  bool domains = false;              ///< also write each particle's domain as a deformed hexahedron
  int history_every = 10;            ///< steps between history.csv rows
  long max_outputs = 1000;           ///< more planned particle files than this is a deck error
  double checkpoint_interval = 0.0;  ///< s of simulated time between checkpoints; 0 = none (docs/restart.md)
  int checkpoint_keep = 2;           ///< newest checkpoints kept in DIR/checkpoints
  /// kg: summary.json's fragment statistics also over the fragments at least this heavy (0: not;
  /// run/fragment_summary.hpp), so that the single points of a fine lattice do not set them.
  double fragment_min_mass = 0.0;
  std::vector<std::int64_t> track;   ///< output.track.ids: particle ids whose full history is recorded
  DeckMark track_mark;               ///< where output.track.ids is (ids are checked against the seeding)
};

/// A preparation stage run before the main stage (thesis seed 000 §5.1: the overburden is
/// ramped and damped to equilibrium, then the damping is released and the penetrator fired).
struct StageSpec {
  std::string name;
  double damping = 0.0;        ///< 1/s, grid damping during the stage (thesis eq. 5.1)
  double duration = 0.0;       ///< s: fixed length (0: ends by the criterion)
  double min_duration = 0.0;   ///< s: the criterion is not checked before this
  double max_duration = 0.0;   ///< s: the criterion must hold by then, or the run stops
  std::string until;           ///< "" (fixed duration) | "stress_equilibrium"
  std::string body;            ///< stress_equilibrium: the body checked
  Vec3 stress;                 ///< Pa: requested diagonal Cauchy stress (xx, yy, zz; axisym rr, zz, theta)
  bool stress_given = false;   ///< false: taken from the body's confinement load
  double tolerance = 0.05;     ///< relative band around the requested stress (thesis: +-5 %)
  double fraction = 1.0;       ///< share of the body's particles that must be in the band (thesis: all)
  int check_every = 10;        ///< steps between checks
  DeckMark mark, body_mark;
};

/// Penetration measurements (thesis seed 000 ch. 5, §7.2): depth and rate against time,
/// penetrator kinetic energy, channel profile.
/// A grid study's record of a deck (validation/convergence_record.py writes it): per quantity the
/// value at each level (by the band's cell) and the converged (Richardson) estimate, with the
/// fingerprint of the physics the levels share (deck/physics_fingerprint.hpp).
struct ConvergenceRecord {
  struct Quantity {
    std::string name;         ///< e.g. cavity_depth
    std::string label;        ///< what it is, for the output ("tunnel depth")
    std::string summary_key;  ///< where a run's summary.json penetration object holds it (dotted)
    double richardson = 0.0;  ///< the converged estimate, SI
    double order = 0.0;       ///< observed order of the three finest levels
    std::vector<std::pair<double, double>> levels;  ///< (band cell m, value SI), coarsest first
  };
  /// A whole configuration (cells and steps included) the study ran once and set against its
  /// converged estimates, being no level of it: e.g. patches of fine cells on the casing.
  struct Checked {
    std::string name;
    std::string label;                                    ///< what it is, for the output
    std::string fingerprint;                              ///< configuration_fingerprint of its resolved deck
    std::vector<std::pair<std::string, double>> values;  ///< (quantity name, value SI): those it measured
  };
  std::string path;         ///< absolute path of the record file ("" when the deck names none)
  std::string study;        ///< where the study is documented
  std::string fingerprint;  ///< physics_fingerprint of the levels' resolved decks
  std::vector<Quantity> quantities;
  std::vector<Checked> checked;
};

struct PenetrationSpec {
  bool enabled = false;
  std::string penetrator;      ///< a rod or jet body, or a shaped charge's `liner` (formed_jet)
  /// The penetrator is a `liner` body: its jet forms in the run (the charge fired at the target in
  /// one deck), so its speed, length and radius are not known before the run.
  bool formed_jet = false;
  /// The line of flight: the rod's or jet's own; for a formed jet the liner's axis, from its apex
  /// towards its mouth (geometry/revolution.hpp), through the apex (`nose`); lengths and speed 0.
  PenetratorSpec flight;
  std::string target;          ///< body whose struck face is the depth origin
  double surface = 0.0;        ///< m: axial coordinate of the target's struck face
  double axis_radius = 0.0;    ///< m: radius around the axis used to find the cavity tip (0: one cell)
  double stop_tolerance = 0.0; ///< m: depth change below which penetration has stopped (0: one cell)
  /// (0, 1): the main stage ends at the first history sample at which every segment of the
  /// penetrator has entered and its kinetic energy is at most this share of its peak; 0: at end_time.
  double end_when_spent = 0.0;
  int rate_half_window = 3;    ///< samples each side of the local-polynomial derivative
  int channel_bins = 0;        ///< bins of the channel profile (0: one per cell of the final depth)
  /// Bodies the penetrator perforates before the target (casing, cement): the hole in each is
  /// measured (entrance and smallest diameter). Default: every body but the penetrator, the target
  /// and any explosive charge.
  std::vector<std::string> layers;
  /// `convergence_record`: the grid study of this deck; the run says which of its levels it is
  /// and how far that level is from converged.
  ConvergenceRecord convergence;
  DeckMark mark;
};

/// One entry of `contact.pairs`: how two bodies meet on the MPM grid.
struct ContactPairSpec {
  std::string body_a, body_b;
  std::string model;      ///< single_field (one shared velocity field) | friction
  double friction = 0.0;  ///< Coulomb coefficient of a friction pair
  DeckMark mark;
};

/// Contact between bodies on the MPM grid. `single_field` (the default) gives every body one
/// velocity field (no-slip, no separation); `friction` gives each body (or each group of bodies
/// joined by single_field pairs) its own velocity field with Coulomb friction where fields meet
/// (Bardenhagen et al., CMAME 187 (2000) 529; CMES 2 (2001) 509; thesis seed 000 ch. 2, Uintah).
struct ContactSpec {
  std::string model = "single_field";  ///< between bodies not listed in pairs
  double friction = 0.0;               ///< Coulomb coefficient of friction pairs without their own
  /// Fields meet at a node only where their particles fill at least this fraction of the node's
  /// volume (a gap check; 0: wherever two fields have mass)
  double min_volume_fraction = 0.0;
  /// Axisymmetric runs: what the contact normal is the gradient of. ring_mass: the points' mass
  /// per radian, rho r A, whose gradient in a uniform body is rho A e_r, not zero, and outweighs a
  /// small body's own gradient within a few cells of the axis; density: the mass per radian over
  /// the point's radius, rho A, as in a planar run
  std::string axisymmetric_normal = "ring_mass";
  std::vector<ContactPairSpec> pairs;
  // Resolved by the deck reader:
  int fields = 1;                      ///< number of velocity fields
  std::vector<int> body_field;         ///< velocity field of each body (deck order)
  std::vector<std::string> field_names;  ///< bodies of each field joined by '+'
  std::vector<double> field_friction;  ///< fields x fields Coulomb coefficients (row-major)
  DeckMark mark;
};

/// One detonator of the `detonation` section: where and when the program burn starts.
struct DetonatorSpec {
  Vec3 position;      ///< m
  double time = 0.0;  ///< s
  DeckMark mark;
};

/// Program burn (seed 001; points/program_burn.hpp): the detonators from which the lighting times
/// of every point of an `explosive` material are computed before time stepping.
struct DetonationSpec {
  std::vector<DetonatorSpec> points;
  double edge_radius = 3.2;  ///< graph edges of the burn search, in lattice spacings
  double burn_cells = 2.0;   ///< burn time of a point, in lattice spacings / D (0: at once)
  DeckMark mark;
};

struct Scenario {
  std::string file;               ///< deck path
  SimulationSpec simulation;
  /// The solver's own deck section (its name is the solver's registered section, e.g. `mpm`),
  /// read against the parameters the solver registered (points/solver_registry.hpp).
  ParamValues solver_params;
  /// Where each solver parameter the deck gave is (key: the parameter's name), and the section.
  std::map<std::string, DeckMark> solver_param_marks;
  DeckMark solver_section_mark;
  GridSpec grid;
  std::vector<MaterialSpec> materials;
  std::vector<BodySpec> bodies;
  std::vector<LoadSpec> loads;
  std::vector<CrackSpec> cracks;  ///< pre-cracks (solvers with bonds only)
  ContactSpec contact;            ///< velocity fields and friction between bodies (MPM)
  DetonationSpec detonation;      ///< program burn of explosive materials
  std::vector<ProbeSpec> probes;
  std::vector<StageSpec> stages;  ///< preparation stages before the main stage
  PenetrationSpec penetration;
  OutputSpec output;
  std::string resolved_yaml;      ///< the deck with every default filled, as YAML text
};

/// Index of the body named `name` in deck order, -1 if there is none (or name is empty).
int body_index(const Scenario& sc, const std::string& name);

/// A DeckError about the solver parameter `key` (a solver's own check, beyond the registered
/// ranges): at the line of its value if the deck gave it, else at the solver's section, else at
/// the file; key path <section>.<key> (`key` empty: the section itself).
[[noreturn]] void throw_solver_param_error(const Scenario& sc, const std::string& section, const std::string& key,
                                           const std::string& message);

}  // namespace ballista
