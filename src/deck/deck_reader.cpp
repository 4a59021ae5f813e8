#include "deck/deck_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "deck/body_ref.hpp"
#include "deck/convergence_record_reader.hpp"
#include "deck/deck_node.hpp"
#include "deck/deck_overrides.hpp"
#include "deck/load_reader.hpp"
#include "deck/material_reader.hpp"
#include "deck/penetrator_reader.hpp"
#include "deck/probe_reader.hpp"
#include "deck/mesh_reader.hpp"
#include "deck/surface_reader.hpp"
#include "deck/text_file.hpp"
#include "geometry/grid_axes.hpp"
#include "geometry/revolution.hpp"
#include "geometry/shape.hpp"
#include "points/initial_state_registry.hpp"
#include "points/probe_registry.hpp"
#include "points/solver_registry.hpp"
#include "scenario/material_model.hpp"

namespace ballista {

const char* dimension_name(Dimension d) {
  switch (d) {
    case Dimension::ThreeD: return "3d";
    case Dimension::PlaneStrain: return "plane_strain";
    case Dimension::Axisymmetric: return "axisymmetric";
  }
  return "?";
}

const char* face_bc_name(FaceBC bc) {
  switch (bc) {
    case FaceBC::Free: return "free";
    case FaceBC::Fixed: return "fixed";
    case FaceBC::Symmetry: return "symmetry";
    case FaceBC::Wall: return "wall";
  }
  return "?";
}

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : axis == 2 ? "z" : "?"; }

int axis_from(const std::string& name) { return name == "x" ? 0 : name == "y" ? 1 : 2; }

namespace {

const std::vector<std::string> kSections{"simulation", "grid",   "materials",   "stages",
                                         "bodies",     "loads",  "cracks",      "contact",
                                         "detonation", "probes", "penetration", "output"};
const std::vector<std::string> kFaces{"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
const std::vector<std::string> kFaceBCs{"free", "fixed", "symmetry", "wall"};
constexpr long kLongMax = LONG_MAX;
constexpr double kSpeedOfLight = 299792458.0;  ///< m/s

FaceBC face_bc_from(const std::string& s) {
  if (s == "fixed") return FaceBC::Fixed;
  if (s == "symmetry") return FaceBC::Symmetry;
  if (s == "wall") return FaceBC::Wall;
  return FaceBC::Free;
}


class Reader {
 public:
  Reader(std::shared_ptr<DeckContext> ctx, YAML::Node doc) : ctx_(ctx), root_(ctx, doc) {}

  Scenario read() {
    sc_.file = ctx_->file;
    // Unknown sections first: a misspelt section name is better reported as such than as a
    // missing required section.
    for (const auto& s : kSections) root_.allow(s);
    for (const auto& f : solver_registry()) root_.allow(f.section);
    root_.finish();
    simulation();
    solver_section();
    grid();
    materials();
    stages();
    bodies();
    read_loads(root_, sc_, confinement_stress_);
    cracks();
    contact();
    detonation();
    read_probes(root_, sc_);
    check_stage_bodies();
    penetration();
    output();
    sc_.resolved_yaml = root_.resolved_text("deck");
    return std::move(sc_);
  }

 private:
  bool two_d() const { return sc_.simulation.dimension != Dimension::ThreeD; }
  int ndim() const { return two_d() ? 2 : 3; }
  int vmin() const { return two_d() ? 2 : 3; }

  void simulation() {
    DeckNode s = root_.map("simulation", true);
    SimulationSpec& sim = sc_.simulation;
    std::vector<std::string> solvers;
    for (const auto& f : solver_registry()) solvers.push_back(f.name);
    sim.solver = s.choice("solver", solvers.empty() ? std::string() : solvers.front(), solvers);
    const std::string dim = s.choice("dimension", "3d", {"3d", "plane_strain", "plane_stress", "axisymmetric"});
    const SolverFactory& solver = *find_solver(sim.solver);
    if (std::find(solver.dimensions.begin(), solver.dimensions.end(), dim) == solver.dimensions.end())
      s.fail("dimension", "solver '" + sim.solver + "' runs in " + join_names(solver.dimensions) +
                              ", not '" + dim + "'");
    sim.plane_stress = dim == "plane_stress";
    sim.dimension = dim == "plane_strain" || dim == "plane_stress" ? Dimension::PlaneStrain
                    : dim == "axisymmetric" ? Dimension::Axisymmetric
                                            : Dimension::ThreeD;
    sim.end_time = s.number("end_time", NumberRange::positive("s"));
    sim.cfl = s.number("cfl", 0.3, NumberRange::between(0.0, 1.0, true, false));
    sim.max_dt = s.number("max_dt", 0.0, NumberRange::non_negative("s"));
    sim.max_steps = s.integer("max_steps", 0, 0, kLongMax);
    sim.step_limit = s.integer("step_limit", 10'000'000, 1, kLongMax);
    sim.damping = s.number("damping", 0.0, NumberRange::non_negative("1/s"));
    sim.energy_drift_limit = s.number("energy_drift_limit", 0.0, NumberRange::non_negative());
    sim.on_particle_exit = s.choice("on_particle_exit", "stop", {"stop", "delete"});
    sim.threads = static_cast<int>(s.integer("threads", 0, 0, 4096));
    s.finish();
  }

  /// The chosen solver's own section, against the parameters it registered; another solver's
  /// section is an error (it would be ignored).
  void solver_section() {
    const SolverFactory& solver = *find_solver(sc_.simulation.solver);
    for (const auto& f : solver_registry())
      if (f.section != solver.section && root_.has(f.section))
        root_.fail(f.section, "section '" + f.section + "' belongs to solver '" + f.name +
                                  "', but simulation.solver is '" + solver.name + "'");
    DeckNode n = root_.map(solver.section, false);
    if (root_.has(solver.section)) sc_.solver_section_mark = root_.mark_of(solver.section);
    for (const ParamSpec& p : solver.params) read_param(n, p.name, p, sc_.solver_params, sc_.solver_param_marks);
    n.finish();
  }

  /// Fails unless upper > lower in every direction used.
  void check_ordered(DeckNode& n, const std::string& upper_key, const Vec3& lo, const Vec3& hi,
                     const std::string& what) {
    for (int d = 0; d < ndim(); ++d)
      if (!(hi[d] > lo[d]))
        n.fail(upper_key, "expected " + what + " greater than lower in every direction; in " + axis_name(d) +
                              " upper is " + format_number(hi[d]) + " and lower " + format_number(lo[d]));
  }

  void grid() {
    DeckNode g = root_.map("grid", true);
    GridSpec& gr = sc_.grid;
    gr.lower = g.vector("lower", vmin());
    gr.upper = g.vector("upper", vmin());
    check_ordered(g, "upper", gr.lower, gr.upper, "upper");
    gr.cell_size = g.number("cell_size", NumberRange::positive("m"));
    const SolverFactory& solver = *find_solver(sc_.simulation.solver);
    // A units check: a box in millimetres read as metres has 10^9 times the cells. A gridless
    // solver allocates none of them (its box only bounds the points), so it may span far more.
    double cells = 1.0;
    for (int d = 0; d < ndim(); ++d) cells *= std::ceil((gr.upper[d] - gr.lower[d]) / gr.cell_size);
    if (cells > (solver.background_grid ? 2.0e9 : 1.0e12))
      g.fail("cell_size", "the grid would have " + format_number(cells) +
                              " cells; check that lengths are in metres");
    DeckNode b = g.map("boundary", false);
    for (int f = 0; f < 6; ++f) {
      gr.faces[f] = face_bc_from(b.choice(kFaces[f], "free", kFaceBCs));
      const auto& allowed = solver.face_conditions;
      if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), gr.faces[f]) == allowed.end())
        b.fail(kFaces[f], "solver '" + solver.name + "' imposes no " + face_bc_name(gr.faces[f]) + " face (" +
                              solver.face_conditions_note + ")");
    }
    if (sc_.simulation.dimension == Dimension::Axisymmetric && gr.lower[0] < 0.0)
      g.fail("lower", "expected x (the radius) >= 0 in an axisymmetric deck, got " + format_number(gr.lower[0]));
    b.finish();
    refine(g, solver);
    patches(g, solver);
    g.finish();
  }

  /// grid.patches: boxes of finer cells with hanging nodes around them (geometry/grid_axes.hpp,
  /// mpm/patch_constraints.hpp), validated by building the axes.
  /// A patch's end as the deck error about it names it.
  static std::string until_text(double until) {
    return std::isfinite(until) ? fmt::format("{:g} s", until) : std::string("not given");
  }

  void patches(DeckNode& g, const SolverFactory& solver) {
    GridSpec& gr = sc_.grid;
    DeckNode ps = g.list("patches", false);
    if (ps.size() > 0 && !solver.graded_grid)
      ps.fail("solver '" + solver.name + "' runs on a uniform lattice: patches are an MPM grid's");
    for (size_t i = 0; i < ps.size(); ++i) {
      DeckNode p = ps.element(i);
      GridPatch patch;
      patch.mark = p.mark();
      patch.lower = p.vector("lower", vmin());
      patch.upper = p.vector("upper", vmin());
      patch.cell_size = p.number("cell_size", NumberRange::positive("m"));
      const std::optional<double> until = p.optional_number("until", NumberRange::positive("s"));
      if (until) patch.until = *until;
      // The grid drops its patches at once: a nested patch kept alone would split its parent's
      // coarse cells in four, which uGIMP refuses (mpm_patches.cpp).
      if (i > 0 && patch.until != gr.patches.front().until)
        p.fail("until", "is " + until_text(patch.until) + " and the first patch's " +
                            until_text(gr.patches.front().until) +
                            ": the grid drops its patches together, so every patch gives the same until (or "
                            "none at all)");
      p.finish();
      gr.patches.push_back(patch);
    }
    if (!gr.patches.empty()) fail_if_too_many_cells(ps, "the grid with its patches");
  }

  /// Builds the axes (their deck errors name the zone or patch) and fails at `at` beyond 2e9 cells.
  void fail_if_too_many_cells(DeckNode& at, const std::string& what) {
    const GridAxes axes_built = build_grid_axes(sc_.grid, ndim());
    double cells = 1.0;
    for (int d = 0; d < ndim(); ++d) cells *= axes_built.cells(d);
    if (cells > 2.0e9) at.fail(what + " would have " + format_number(cells) + " cells; check that lengths are in metres");
  }

  /// grid.refine and grid.grading: bands of finer cells (a graded grid, geometry/grid_axes.hpp),
  /// validated by building the axes (a zone outside the box, overlapping zones, a gap too short to
  /// grade are errors at the zone).
  void refine(DeckNode& g, const SolverFactory& solver) {
    GridSpec& gr = sc_.grid;
    gr.grading = g.number("grading", 1.2, NumberRange::between(1.05, 2.0));
    DeckNode zs = g.list("refine", false);
    if (zs.size() > 0) gr.refine_mark = g.mark_of("refine");
    if (zs.size() > 0 && !solver.graded_grid)
      zs.fail("solver '" + solver.name + "' runs on a uniform lattice: refine zones are an MPM grid's");
    std::vector<std::string> axes{"x", "y"};
    if (!two_d()) axes.push_back("z");
    for (size_t i = 0; i < zs.size(); ++i) {
      DeckNode z = zs.element(i);
      RefineZone zone;
      zone.mark = z.mark();
      zone.axis = axis_from(z.choice("axis", axes));
      zone.from = z.number("from", NumberRange::any("m"));
      zone.to = z.number("to", NumberRange::any("m"));
      zone.cell_size = z.number("cell_size", NumberRange::positive("m"));
      z.finish();
      gr.refine.push_back(zone);
    }
    if (!gr.refine.empty()) fail_if_too_many_cells(zs, "the graded grid");
  }

  void materials() {
    DeckNode ms = root_.map("materials", true);
    const auto names = ms.entry_names();
    if (names.empty()) ms.fail("expected at least one material (name: {model: ..., parameters})");
    for (const auto& name : names) sc_.materials.push_back(read_material_spec(ms, name));
    ms.finish();
  }

  ShapeSpec shape(DeckNode& s) {
    ShapeSpec sh;
    const bool axi = sc_.simulation.dimension == Dimension::Axisymmetric;
    const bool plane = sc_.simulation.dimension == Dimension::PlaneStrain;
    sh.type = s.choice("type", {"box", "sphere", "cylinder", "tube", "cone", "liner", "revolution", "surface", "mesh"});
    if (sh.type == "surface" || sh.type == "mesh") {
      if (sc_.simulation.dimension != Dimension::ThreeD)
        s.fail("type", "a " + sh.type + " shape fills a 3D body: the deck's simulation.dimension must be 3d");
      return sh.type == "surface" ? read_surface_shape(s) : read_mesh_shape(s);
    }
    if (sh.type == "box") {
      sh.lower = s.vector("lower", vmin());
      sh.upper = s.vector("upper", vmin());
      check_ordered(s, "upper", sh.lower, sh.upper, "upper");
      if (axi && sh.lower[0] < 0.0)
        s.fail("lower", "expected x (the radius) >= 0 in an axisymmetric deck, got " + format_number(sh.lower[0]));
    } else if (sh.type == "sphere") {
      sh.center = s.vector("center", vmin());
      sh.radius = s.number("radius", NumberRange::positive("m"));
      if (axi && sh.center[0] != 0.0)
        s.fail("center", "expected x = 0 in an axisymmetric deck (the centre must lie on the axis), got " +
                             format_number(sh.center[0]));
    } else if (sh.type == "cone" || sh.type == "liner" || sh.type == "revolution") {
      revolution_shape(s, sh);
    } else {  // cylinder, tube
      sh.center = s.vector("center", vmin());
      const std::string ax = s.choice("axis", {"x", "y", "z"});
      sh.axis = axis_from(ax);
      sh.radius = s.number("radius", NumberRange::positive("m"));
      if (sh.type == "tube") {
        sh.inner_radius = s.number("inner_radius", NumberRange::positive("m"));
        if (!(sh.inner_radius < sh.radius))
          s.fail("inner_radius", "expected inner_radius < radius (" + format_number(sh.radius) + " m), got " +
                                     format_number(sh.inner_radius));
      }
      if (plane && sh.axis == 2)  // a disk (or annulus) in the x-y plane: length unused
        sh.length = s.number("length", 0.0, NumberRange::non_negative("m"));
      else
        sh.length = s.number("length", NumberRange::positive("m"));
      if (axi && sh.axis != 1)
        s.fail("axis", "expected axis y in an axisymmetric deck (the symmetry axis), got " + ax);
      if (axi && sh.center[0] != 0.0)
        s.fail("center", "expected x = 0 in an axisymmetric deck (the base centre must lie on the axis), got " +
                             format_number(sh.center[0]));
    }
    s.finish();
    return sh;
  }

  /// A solid of revolution (geometry/revolution.hpp): `center` on the axis, `axis`, and the section
  /// as a frustum (cone), a conical shell (liner) or a polygon (revolution outline).
  void revolution_shape(DeckNode& s, ShapeSpec& sh) {
    const bool axi = sc_.simulation.dimension == Dimension::Axisymmetric;
    const bool plane = sc_.simulation.dimension == Dimension::PlaneStrain;
    sh.center = s.vector("center", vmin());
    const std::string ax = s.choice("axis", {"x", "y", "z"});
    sh.axis = axis_from(ax);
    if (axi && sh.axis != 1)
      s.fail("axis", "expected axis y in an axisymmetric deck (the symmetry axis), got " + ax);
    if (plane && sh.axis == 2)
      s.fail("axis", "expected axis x or y in a plane-strain deck (the shape's axial section lies in the x-y plane), "
                     "got z");
    if (axi && sh.center[0] != 0.0)
      s.fail("center", "expected x = 0 in an axisymmetric deck (the axis of the shape is the symmetry axis), got " +
                           format_number(sh.center[0]));
    if (sh.type == "cone") {
      sh.radius = s.number("radius", NumberRange::non_negative("m"));
      sh.top_radius = s.number("top_radius", 0.0, NumberRange::non_negative("m"));
      sh.length = s.number("length", NumberRange::positive("m"));
      if (!(sh.radius > 0.0 || sh.top_radius > 0.0))
        s.fail("radius", "expected radius or top_radius > 0 (both 0 is a line, not a cone)");
      sh.outline = cone_outline(sh.radius, sh.top_radius, sh.length);
    } else if (sh.type == "liner") {
      sh.angle = s.number("angle", NumberRange::between(0.0, 180.0, true, true, "degrees"));
      sh.thickness = s.number("thickness", NumberRange::positive("m"));
      const double diameter = s.number("diameter", NumberRange::positive("m"));
      sh.radius = 0.5 * diameter;
      const double limit = sh.radius * std::cos(0.5 * sh.angle * M_PI / 180.0);
      if (!(sh.thickness < limit))
        s.fail("thickness", "expected a wall thinner than (diameter / 2) cos(angle / 2) = " + format_number(limit) +
                                " m, where the inner cone would close before the mouth; got " +
                                format_number(sh.thickness));
      sh.outline = liner_outline(sh.angle, sh.thickness, diameter);
    } else {
      const YAML::Node v = s.raw("outline");
      const std::string what = "a list of at least 3 vertices [r, a] (m): radius from the axis and distance along it "
                               "from center";
      if (!v.IsSequence() || v.size() < 3) s.fail("outline", "expected " + what);
      // Its resolved form, written back: the resolved deck a run keeps (and restarts compare)
      // must carry the section, or it would neither re-read nor tell two outlines apart.
      YAML::Node out(YAML::NodeType::Sequence);
      for (size_t i = 0; i < v.size(); ++i) {
        const std::string path = s.child_path("outline") + "." + std::to_string(i);
        const YAML::Node r = v[i];
        if (!r.IsSequence() || r.size() != 2) deck_fail(s.context(), path, r.Mark(), "expected " + what);
        double x[2];
        for (int k = 0; k < 2; ++k)
          if (!scalar_number(r[k], x[k])) deck_fail(s.context(), path + "." + std::to_string(k), r[k].Mark(), "expected a number");
        sh.outline.push_back({x[0], x[1]});
        YAML::Node pair(YAML::NodeType::Sequence);
        pair.SetStyle(YAML::EmitterStyle::Flow);
        pair.push_back(DeckNode::number_node(x[0]));
        pair.push_back(DeckNode::number_node(x[1]));
        out.push_back(pair);
      }
      s.set_resolved("outline", out);
    }
    if (const auto problem = outline_problem(sh.outline))
      s.fail(sh.type == "revolution" ? "outline" : "type", "the " + sh.type + "'s section: " + *problem);
  }

  const BodySpec* find_body(const std::string& name) const {
    for (const auto& b : sc_.bodies)
      if (b.name == name) return &b;
    return nullptr;
  }

  std::vector<std::string> body_names() const {
    std::vector<std::string> n;
    for (const auto& b : sc_.bodies) n.push_back(b.name);
    return n;
  }

  /// Whether the deck's solver (already read and checked) has a capability of its registration.
  bool solver_can(bool SolverFactory::*capability) const {
    const SolverFactory* f = find_solver(sc_.simulation.solver);
    return f && f->*capability;
  }
  /// The solvers with a capability, for a message ("mpm", "mpm or otm").
  static std::string solvers_that(bool SolverFactory::*capability) {
    std::string out;
    for (const SolverFactory& f : solver_registry())
      if (f.*capability) out += (out.empty() ? "" : " or ") + f.name;
    return out.empty() ? "no solver" : out;
  }

  /// Reads `key` as the name of a defined body ("" allowed if optional and absent).
  std::string body_ref(DeckNode& n, bool required) { return read_body_ref(n, sc_, required); }


  void bodies() {
    DeckNode bs = root_.list("bodies", true);
    if (bs.size() == 0) bs.fail("expected at least one body");
    std::vector<std::string> materials;
    for (const auto& m : sc_.materials) materials.push_back(m.name);
    for (size_t i = 0; i < bs.size(); ++i) {
      DeckNode b = bs.element(i);
      BodySpec body;
      body.mark = b.mark();
      body.name = b.string("name");
      if (const BodySpec* other = find_body(body.name))
        b.fail("name", "duplicate body name '" + body.name + "' (also " + other->mark.key_path +
                           (other->mark.line > 0 ? " at line " + std::to_string(other->mark.line) : "") + ")");
      body.material = b.string("material");
      if (std::find(materials.begin(), materials.end(), body.material) == materials.end())
        b.fail("material", "unknown material '" + body.material + "'" + suggest(body.material, materials));
      body.seeding = b.choice("seeding", "lattice", {"lattice", "cut_lattice", "elements"});
      if (body.seeding == "cut_lattice" && !solver_can(&SolverFactory::cut_lattice))
        b.fail("seeding", "points cut to the surface have unequal volumes off the lattice's sites, for solvers "
                          "that take them (" + solvers_that(&SolverFactory::cut_lattice) + "); solver '" +
                              sc_.simulation.solver + "' builds on the regular lattice (seeding: lattice)");
      if (body.seeding == "elements") {
        if (!solver_can(&SolverFactory::element_seeding))
          b.fail("seeding", "points at a mesh's elements are for solvers whose nodes are the mesh's vertices (" +
                                solvers_that(&SolverFactory::element_seeding) + "); solver '" +
                                sc_.simulation.solver + "' seeds a lattice inside the mesh (seeding: lattice)");
        if (b.has("particles_per_cell"))
          b.fail("particles_per_cell", "a body seeded at its mesh's elements has one point per tetrahedron; "
                                       "particles_per_cell applies to seeding: lattice");
      }
      // Not read for element seeding, so that resolved.yaml (which a restart reads) does not list it.
      if (body.seeding != "elements") body.particles_per_cell = static_cast<int>(b.integer("particles_per_cell", 2, 1, 8));
      body.point_spacing = b.optional_number("point_spacing", NumberRange::positive("m")).value_or(0.0);
      if (body.point_spacing > 0.0 && !solver_can(&SolverFactory::point_spacing))
        b.fail("point_spacing", "a body's own lattice spacing is a peridynamics key (solver '" + sc_.simulation.solver +
                                    "' seeds particles_per_cell per grid cell)");
      body.activation_time = b.number("activation_time", 0.0, NumberRange::non_negative("s"));
      // Exactly one of shape (a plain body), rod or jet (penetrators made of segments).
      const int given = int(b.has("shape")) + int(b.has("rod")) + int(b.has("jet"));
      if (given != 1)
        b.fail("expected exactly one of shape (a solid), rod (a solid or segmented rod) or jet (a discrete "
               "shaped-charge jet), got " + std::to_string(given));
      if (b.has("shape")) {
        DeckNode s = b.map("shape", true);
        body.shape = shape(s);
        DeckNode cuts = b.list("cutouts", false);
        if (body.seeding == "elements" && cuts.size() > 0)
          b.fail("cutouts", "a body seeded at its mesh's elements takes no cutouts (an element cut in part "
                            "would keep its whole volume): leave the material out of the mesh");
        for (size_t i = 0; i < cuts.size(); ++i) {
          DeckNode c = cuts.element(i);
          body.cutouts.push_back(shape(c));
        }
        body.velocity = b.vector("velocity", Vec3{}, vmin());
        // Beyond the speed of light a velocity is a typo or an overflow, never an impact.
        if (norm(body.velocity) >= kSpeedOfLight)
          b.fail("velocity", "expected a speed below the speed of light (2.998e8 m/s), got " +
                                 format_number(norm(body.velocity)) + " m/s");
        body.radial_speed =
            b.number("radial_velocity", 0.0,
                     NumberRange::between(-kSpeedOfLight, kSpeedOfLight, true, true, "m/s"));
        if (body.radial_speed != 0.0 && body.shape.type != "cylinder" && body.shape.type != "tube")
          b.fail("radial_velocity", "a radial velocity is away from the axis of a cylinder or tube; body '" +
                                        body.name + "' is a " + body.shape.type);
        b.allow("rod");
        b.allow("jet");
      } else {
        if (b.has("velocity"))
          b.fail("velocity", "a rod or jet gets its velocity from its speed (rod) or segment table (jet)");
        DeckNode pn = b.map(b.has("rod") ? "rod" : "jet", true);
        if (b.has("rod")) read_rod(pn, sc_.simulation.dimension, sc_.grid, body);
        else read_jet(pn, sc_.simulation.dimension, sc_.grid, body);
        b.allow("shape");
        b.allow("velocity");
      }
      if (body.seeding == "elements" && body.shape.type != "mesh")
        b.fail("seeding", "seeding: elements places the points at a mesh's elements; body '" + body.name + "' is " +
                              (body.penetrator.kind.empty() ? "a " + body.shape.type : "a " + body.penetrator.kind) +
                              " (give shape: {type: mesh, file: ...})");
      // Penetrators are fired in the main stage; other bodies start with the first stage.
      body.activation_stage =
          stage_ref(b, "activation_stage",
                    body.penetrator.kind.empty() ? 0 : static_cast<int>(sc_.stages.size()));
      std::vector<std::string> states{"none"};
      for (const InitialStateFactory& f : initial_state_registry()) states.push_back(f.name);
      body.initial_state = b.choice("initial_state", "none", states);
      if (const InitialStateFactory* state = find_initial_state(body.initial_state); state && state->check)
        if (const std::optional<BodyIssue> issue = state->check(body)) b.fail(issue->key, issue->message);
      b.finish();
      Vec3 lo, hi;
      shape_bounds(body.shape, ndim(), lo, hi);
      for (int d = 0; d < ndim(); ++d)
        if (hi[d] < sc_.grid.lower[d] || lo[d] > sc_.grid.upper[d])
          b.fail("shape", "body '" + body.name + "' lies entirely outside the grid (in " + axis_name(d) +
                              " it spans " + format_number(lo[d]) + " to " + format_number(hi[d]) +
                              ", the grid " + format_number(sc_.grid.lower[d]) + " to " +
                              format_number(sc_.grid.upper[d]) + ")");
      sc_.bodies.push_back(std::move(body));
    }
  }

  /// `cracks`: pre-cracks and notches cut into the bonds before the run (peridynamics).
  void cracks() {
    DeckNode cs = root_.list("cracks", false);
    if (cs.size() > 0 && !solver_can(&SolverFactory::pre_cracks))
      cs.fail("pre-cracks cut bonds: solver '" + sc_.simulation.solver + "' has none (" +
              solvers_that(&SolverFactory::pre_cracks) + " has them)");
    for (size_t i = 0; i < cs.size(); ++i) {
      DeckNode c = cs.element(i);
      CrackSpec crack;
      crack.mark = c.mark();
      crack.body = body_ref(c, false);
      crack.from = c.vector("from", 2);
      crack.to = c.vector("to", 2);
      if (crack.from[0] == crack.to[0] && crack.from[1] == crack.to[1])
        c.fail("to", "expected a segment of non-zero length in the x-y plane (from and to coincide)");
      c.finish();
      sc_.cracks.push_back(crack);
    }
  }

  /// `detonation`: the detonators of the program burn (seed 001). Required when a material is an
  /// `explosive` (a charge that never lights is refused: say so with a detonator at a late time).
  void detonation() {
    DeckNode d = root_.map("detonation", false);
    DetonationSpec& ds = sc_.detonation;
    ds.mark = d.mark();
    ds.edge_radius = d.number("edge_radius", 3.2, NumberRange::between(1.5, 10.0));
    ds.burn_cells = d.number("burn_cells", 2.0, NumberRange::between(0.0, 20.0));
    DeckNode ps = d.list("points", false);
    for (size_t i = 0; i < ps.size(); ++i) {
      DeckNode p = ps.element(i);
      DetonatorSpec det;
      det.mark = p.mark();
      det.position = p.vector("position", vmin());
      det.time = p.number("time", 0.0, NumberRange::non_negative("s"));
      // Lighting times are sums of this time and path lengths over the detonation speed: beyond
      // a second (a million times a munition's run) they mean "never", which is what an
      // explosive that no body uses says.
      if (det.time > 1.0)
        p.fail("time", "expected a detonation time of at most 1 s, got " + format_number(det.time) +
                           " s; a charge that must not go off during the run can be lit at any time after "
                           "simulation.end_time");
      p.finish();
      ds.points.push_back(det);
    }
    d.finish();
    // What lights is a body of an explosive material; an explosive material no body uses is inert.
    std::string charge;
    for (const BodySpec& b : sc_.bodies)
      if (charge.empty() && body_of_model(sc_, b, "explosive")) charge = b.name;
    const MaterialSpec* unused = first_material_of_model(sc_, "explosive");
    if (!charge.empty() && ds.points.empty())
      d.fail("points", "body '" + charge + "' is an explosive: give at least one detonator, e.g. "
                       "detonation: {points: [{position: [0, 0, 0], time: 0}]}");
    if (charge.empty() && !ds.points.empty())
      d.fail("points", unused ? "detonators are given but no body is made of an explosive material (material '" +
                                    unused->name + "' is one, and no body uses it)"
                              : "detonators are given but no material has model: explosive");
  }

  /// `contact`: velocity fields and Coulomb friction between bodies on the MPM grid. Bodies are
  /// grouped into fields: each body its own, joined by single_field pairs (and, under the default
  /// model single_field, every pair not listed as friction); a friction pair must end up in two
  /// different fields.
  void contact() {
    DeckNode c = root_.map("contact", false);
    ContactSpec& cs = sc_.contact;
    cs.mark = c.mark();
    const std::vector<std::string> models{"single_field", "friction"};
    cs.model = c.choice("model", "single_field", models);
    cs.friction = c.number("friction", 0.0, NumberRange::non_negative("1"));
    cs.min_volume_fraction = c.number("min_volume_fraction", 0.0, NumberRange::between(0.0, 1.0, false, false, "1"));
    cs.axisymmetric_normal = c.choice("axisymmetric_normal", "ring_mass", {"ring_mass", "density"});
    // resolved.yaml states the default of every run, so only another value is refused elsewhere.
    if (cs.axisymmetric_normal != "ring_mass" && sc_.simulation.dimension != Dimension::Axisymmetric)
      c.fail("axisymmetric_normal", "applies to axisymmetric runs only (simulation.dimension: axisymmetric)");
    DeckNode ps = c.list("pairs", false);
    const int nb = static_cast<int>(sc_.bodies.size());
    std::vector<int> parent(nb);
    for (int b = 0; b < nb; ++b) parent[b] = b;
    auto root = [&](int b) {
      while (parent[b] != b) b = parent[b] = parent[parent[b]];
      return b;
    };
    std::vector<std::vector<int>> listed(nb, std::vector<int>(nb, -1));  // pair index per body pair
    for (size_t i = 0; i < ps.size(); ++i) {
      DeckNode p = ps.element(i);
      ContactPairSpec pair;
      pair.mark = p.mark();
      const std::vector<std::string> names = p.strings("bodies", {});
      if (names.size() != 2) p.fail("bodies", "expected the names of two bodies, e.g. [jet, casing]");
      for (const std::string& n : names)
        if (!find_body(n)) p.fail("bodies", "unknown body '" + n + "'" + suggest(n, body_names()));
      if (names[0] == names[1]) p.fail("bodies", "expected two different bodies");
      pair.body_a = names[0];
      pair.body_b = names[1];
      pair.model = p.choice("model", "friction", models);
      pair.friction = pair.model == "friction"
                          ? p.number("friction", cs.friction, NumberRange::non_negative("1"))
                          : 0.0;
      p.finish();
      const int a = body_index(sc_, pair.body_a), b = body_index(sc_, pair.body_b);
      if (listed[a][b] >= 0)
        p.fail("bodies", "the pair " + pair.body_a + "–" + pair.body_b + " is already listed (contact.pairs." +
                             std::to_string(listed[a][b]) + ")");
      listed[a][b] = listed[b][a] = static_cast<int>(i);
      if (pair.model == "single_field") parent[root(a)] = root(b);
      cs.pairs.push_back(pair);
    }
    c.finish();
    if (cs.model == "single_field")
      for (int a = 0; a < nb; ++a)
        for (int b = a + 1; b < nb; ++b)
          if (listed[a][b] < 0) parent[root(a)] = root(b);
    // Fields numbered in order of their first body.
    std::vector<int> field_of_root(nb, -1);
    cs.body_field.assign(nb, 0);
    cs.field_names.clear();
    for (int b = 0; b < nb; ++b) {
      const int r = root(b);
      if (field_of_root[r] < 0) {
        field_of_root[r] = static_cast<int>(cs.field_names.size());
        cs.field_names.push_back(sc_.bodies[b].name);
      } else {
        cs.field_names[field_of_root[r]] += "+" + sc_.bodies[b].name;
      }
      cs.body_field[b] = field_of_root[r];
    }
    cs.fields = static_cast<int>(cs.field_names.size());
    const int nf = cs.fields;
    cs.field_friction.assign(static_cast<size_t>(nf) * nf, cs.friction);
    std::vector<int> set_by(static_cast<size_t>(nf) * nf, -1);
    for (size_t i = 0; i < cs.pairs.size(); ++i) {
      const ContactPairSpec& pair = cs.pairs[i];
      if (pair.model != "friction") continue;
      const int fa = cs.body_field[body_index(sc_, pair.body_a)], fb = cs.body_field[body_index(sc_, pair.body_b)];
      const DeckMark& m = pair.mark;
      if (fa == fb)
        throw DeckError(m.file, m.line, m.column, m.key_path,
                        "bodies " + pair.body_a + " and " + pair.body_b + " share one velocity field (" +
                            cs.field_names[fa] + ", joined by single_field pairs), so they cannot slide: "
                            "list the pairs that join them as friction, or set contact.model: friction");
      const size_t k = static_cast<size_t>(fa) * nf + fb;
      if (set_by[k] >= 0 && cs.field_friction[k] != pair.friction)
        throw DeckError(m.file, m.line, m.column, m.key_path,
                        "friction " + format_number(pair.friction) + " between fields " + cs.field_names[fa] + " and " +
                            cs.field_names[fb] + " contradicts contact.pairs." + std::to_string(set_by[k]) +
                            " (friction " + format_number(cs.field_friction[k]) + ")");
      cs.field_friction[k] = cs.field_friction[static_cast<size_t>(fb) * nf + fa] = pair.friction;
      set_by[k] = set_by[static_cast<size_t>(fb) * nf + fa] = static_cast<int>(i);
    }
    if (nf > 1 && !solver_can(&SolverFactory::velocity_fields))
      c.fail("model", "separate velocity fields are a grid contact of " +
                          solvers_that(&SolverFactory::velocity_fields) + "; solver '" +
                          sc_.simulation.solver + "' has its own contact (docs/deck.md)");
  }

  /// Index of the stage named by `key` (a name under `stages`, or `main`); `fallback` if absent.
  int stage_ref(DeckNode& n, const std::string& key, int fallback) {
    std::vector<std::string> names;
    for (const auto& st : sc_.stages) names.push_back(st.name);
    names.push_back("main");
    const std::string dflt = names.at(static_cast<size_t>(fallback));
    const std::string name = n.defined_name(key, dflt, names);
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  }

  /// Preparation stages (thesis seed 000 §5.1): each ends after a fixed duration or when its
  /// criterion holds (stress_equilibrium: every particle of the body within +-tolerance of the
  /// requested stress), with its own grid damping (eq. 5.1).
  void stages() {
    DeckNode ss = root_.list("stages", false);
    for (size_t i = 0; i < ss.size(); ++i) {
      DeckNode n = ss.element(i);
      StageSpec st;
      st.mark = n.mark();
      st.name = n.string("name");
      if (st.name == "main")
        n.fail("name",
               "'main' is the name of the final stage (simulation.end_time); choose another");
      for (const auto& other : sc_.stages)
        if (other.name == st.name) n.fail("name", "duplicate stage name '" + st.name + "'");
      st.damping = n.number("damping", 0.0, NumberRange::non_negative("1/s"));
      if (n.has("until")) {
        DeckNode u = n.map("until", true);
        st.until = u.choice("type", {"stress_equilibrium"});
        st.body = u.string("body");  // checked against the bodies once they are read
        st.body_mark = u.mark_of("body");
        // Requested stress: given, or (checked once the loads are read) that of the body's confinement.
        st.stress_given = u.has("stress");
        if (st.stress_given) st.stress = u.vector("stress", 3);
        else u.allow("stress");
        st.tolerance = u.number("tolerance", 0.05, NumberRange::between(0.0, 1.0, true, true));
        st.fraction = u.number("fraction", 1.0, NumberRange::between(0.0, 1.0, true, false));
        st.check_every = static_cast<int>(u.integer("check_every", 10, 1, INT_MAX));
        u.finish();
        st.min_duration = n.number("min_duration", 0.0, NumberRange::non_negative("s"));
        st.max_duration = n.number("max_duration", NumberRange::positive("s"));
        if (st.min_duration > st.max_duration)
          n.fail("min_duration", "expected min_duration <= max_duration (" + format_number(st.max_duration) + " s)");
        n.allow("duration");
        if (n.has("duration"))
          n.fail("duration",
                 "a stage ends either after a duration or by its `until` criterion, not both");
      } else {
        n.allow("until");
        st.duration = n.number("duration", NumberRange::positive("s"));
        n.allow("min_duration");
        n.allow("max_duration");
      }
      n.finish();
      sc_.stages.push_back(std::move(st));
    }
  }

  void check_stage_bodies() {
    for (StageSpec& st : sc_.stages) {
      if (st.until.empty()) continue;
      const DeckMark& m = st.body_mark;
      if (!find_body(st.body))
        throw DeckError(m.file, m.line, m.column, m.key_path,
                        "unknown body '" + st.body + "'" + suggest(st.body, body_names()));
      if (st.stress_given) continue;
      const auto c = confinement_stress_.find(st.body);
      if (c == confinement_stress_.end())
        throw DeckError(m.file, m.line, m.column, m.key_path,
                        "body '" + st.body + "' has no confinement load: give until.stress [xx, yy, zz] (Pa)");
      st.stress = c->second;
    }
  }

  /// Penetration measurements (thesis seed 000 ch. 5, §7.2): the penetrator must be a rod or jet,
  /// or a shaped charge's liner whose jet forms in the run.
  void penetration() {
    if (!root_.has("penetration")) return;  // (an empty map would re-read as a section to fill)
    DeckNode n = root_.map("penetration", true);
    PenetrationSpec& pe = sc_.penetration;
    pe.enabled = true;
    pe.mark = n.mark();
    pe.penetrator = n.string("penetrator");
    const BodySpec* pb = find_body(pe.penetrator);
    if (!pb) n.fail("penetrator", "unknown body '" + pe.penetrator + "'" + suggest(pe.penetrator, body_names()));
    pe.formed_jet = pb->penetrator.kind.empty() && pb->shape.type == "liner";
    if (pb->penetrator.kind.empty() && !pe.formed_jet)
      n.fail("penetrator",
             "body '" + pe.penetrator +
                 "' is not a rod, a jet or a liner (give it `rod:` or `jet:` instead of `shape:`, or a `liner` "
                 "shape whose jet forms in the run)");
    pe.flight = pb->penetrator;
    if (pe.formed_jet) {  // the jet leaves the liner along its axis, from the apex towards the mouth
      pe.flight = PenetratorSpec{};
      pe.flight.kind = "liner";
      pe.flight.axis = pb->shape.axis;
      pe.flight.direction = 1.0;
      pe.flight.nose = pb->shape.center;
    }
    pe.target = n.string("target");
    const BodySpec* tb = find_body(pe.target);
    if (!tb) n.fail("target", "unknown body '" + pe.target + "'" + suggest(pe.target, body_names()));
    if (tb == pb) n.fail("target", "the target must differ from the penetrator");
    // Default surface: the target's face towards the incoming penetrator.
    Vec3 lo, hi;
    shape_bounds(tb->shape, ndim(), lo, hi);
    const PenetratorSpec& ps = pe.flight;
    const double face = ps.direction < 0 ? hi[ps.axis] : lo[ps.axis];
    pe.surface = n.number("surface", face, NumberRange::any("m"));
    // "One cell": on a graded grid the finest of its bands across the line of flight, where the jet
    // is; a patch refines a box, not the path (the probe reads the jet's cells the same way).
    double cell = sc_.grid.cell_size;
    if (sc_.grid.graded()) {
      const GridAxes bands = build_base_axes(sc_.grid, ndim());
      cell = INFINITY;
      for (int a = 0; a < ndim(); ++a)
        if (a != ps.axis) cell = std::min(cell, bands.smallest(a));
    }
    pe.axis_radius = n.number("axis_radius", cell, NumberRange::positive("m"));
    pe.stop_tolerance = n.number("stop_tolerance", cell, NumberRange::positive("m"));
    // A share of the penetrator's peak kinetic energy; 0 (absent) ends the run at end_time.
    pe.end_when_spent = n.number("end_when_spent", 0.0, NumberRange::between(0.0, 1.0, false, true, "1"));
    pe.rate_half_window = static_cast<int>(n.integer("rate_half_window", 3, 1, 1000));
    pe.channel_bins = static_cast<int>(n.integer("channel_bins", 0, 0, 100000));
    // Default layers: every other body but a charge (explosive), which drives the penetrator and is
    // not perforated by it.
    std::vector<std::string> others;
    for (const BodySpec& b : sc_.bodies)
      if (b.name != pe.penetrator && b.name != pe.target && !body_of_model(sc_, b, "explosive"))
        others.push_back(b.name);
    pe.layers = n.strings("layers", others);
    for (const std::string& l : pe.layers) {
      if (!find_body(l)) n.fail("layers", "unknown body '" + l + "'" + suggest(l, body_names()));
      if (l == pe.penetrator || l == pe.target)
        n.fail("layers", "'" + l +
                             "' is the penetrator or the target; layers are the bodies perforated "
                             "before the target");
    }
    pe.convergence = read_convergence_record(n);
    n.finish();
  }

  void output() {
    DeckNode o = root_.map("output", false);
    OutputSpec& out = sc_.output;
    out.interval = o.number("interval", 0.0, NumberRange::non_negative("s"));
    out.fields = o.strings("fields", {});
    out.domains = o.boolean("domains", false);
    out.history_every = static_cast<int>(o.integer("history_every", 10, 1, INT_MAX));
    out.max_outputs = o.integer("max_outputs", 1000, 1, kLongMax);
    out.checkpoint_interval = o.number("checkpoint_interval", 0.0, NumberRange::non_negative("s"));
    out.checkpoint_keep = static_cast<int>(o.integer("checkpoint_keep", 2, 1, 1000));
    // Optional: absent, the resolved deck is what it was without the key.
    out.fragment_min_mass = o.optional_number("fragment_min_mass", NumberRange::positive("kg")).value_or(0.0);
    if (out.interval > 0.0) {
      // Particle files of the run: the first, one per interval of the main stage, one per
      // preparation stage and the last (an interval of 1e-12 s would write one 300 kB file per step).
      const double planned = std::ceil(sc_.simulation.end_time / out.interval) + 2.0 + sc_.stages.size();
      if (planned > static_cast<double>(out.max_outputs))
        o.fail("interval", "an output every " + format_number(out.interval) + " s over end_time " +
                               format_number(sc_.simulation.end_time) + " s writes " +
                               (std::isfinite(planned) ? "about " + format_number(planned)
                                                       : std::string("more than 1e308")) +
                               " particle files, more than output.max_outputs = " +
                               std::to_string(out.max_outputs) +
                               "; lengthen the interval, or raise output.max_outputs to insist");
    }
    DeckNode tr = o.map("track", false);
    out.track = particle_ids(tr, "ids");
    out.track_mark = tr.mark_of("ids");
    tr.finish();
    o.finish();
  }

  /// A list of distinct particle ids (integers >= 0); absent = empty.
  std::vector<std::int64_t> particle_ids(DeckNode& n, const std::string& key) {
    std::vector<std::int64_t> ids;
    const YAML::Node v = n.raw(key);
    YAML::Node out(YAML::NodeType::Sequence);
    out.SetStyle(YAML::EmitterStyle::Flow);
    if (v.IsDefined() && !v.IsNull()) {
      if (!v.IsSequence()) n.fail(key, "expected a list of particle ids (integers >= 0)");
      for (size_t i = 0; i < v.size(); ++i) {
        const YAML::Node x = v[i];
        const std::string path = n.child_path(key) + "." + std::to_string(i);
        double d = 0.0;
        if (!scalar_number(x, d) || d != std::floor(d) || d < 0.0 || d > 9e15)
          deck_fail(*ctx_, path, x.Mark(),
                    "expected a particle id (an integer >= 0), got " +
                        (x.IsScalar() ? "'" + shorten(x.Scalar()) + "'" : std::string("a list or map")));
        const auto id = static_cast<std::int64_t>(d);
        if (std::find(ids.begin(), ids.end(), id) != ids.end())
          deck_fail(*ctx_, path, x.Mark(), "particle id " + std::to_string(id) + " is listed twice");
        ids.push_back(id);
        out.push_back(std::to_string(id));
      }
    }
    n.set_resolved(key, out);
    return ids;
  }

  std::shared_ptr<DeckContext> ctx_;
  DeckNode root_;
  Scenario sc_;
  std::map<std::string, Vec3> confinement_stress_;  ///< body -> equilibrium stress of its confinement load
};

}  // namespace

Scenario parse_deck(const std::string& yaml_text, const std::string& file_name,
                    const std::vector<std::string>& overrides) {
  DeckDocument d =
      open_deck_document(yaml_text, file_name, overrides, "deck", "simulation, grid, materials, bodies, ...");
  Reader reader(d.ctx, d.root);
  return reader.read();
}

Scenario read_deck(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_deck(read_input_file(path, "", "the deck file"), path, overrides);
}

}  // namespace ballista
