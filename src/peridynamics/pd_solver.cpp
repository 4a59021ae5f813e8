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
#include "geometry/seeding.hpp"
#include "geometry/shape.hpp"
#include "peridynamics/bond_pass.hpp"
#include "peridynamics/fragments.hpp"
#include "points/rcb_partition.hpp"
#include "points/solver_registry.hpp"
#include "scenario/material_model.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
/// Storage per bond end: the family (BondFamily::kBytesPerBond) plus the half-bond pass's mirror
/// position and inverse length (the micro-plastic stretch adds 8 B when present).
constexpr double kSolverBytesPerBond = pd::BondFamily::kBytesPerBond + sizeof(std::int32_t) + sizeof(double);

/// A DeckError at a key of the peridynamics section (the solver checks what the specs cannot),
/// at the key's line.
[[noreturn]] void section_error(const Scenario& sc, const std::string& key, const std::string& message) {
  throw_solver_param_error(sc, "peridynamics", key, message);
}

/// Bond ends per point of a full family (the memory estimate; fewer near a surface).
double full_family_size(const Scenario& sc) {
  const ParamValues& P = sc.solver_params;
  const double dx = sc.grid.cell_size;
  const double delta = P.given("horizon") ? P.at("horizon") : (P.given("m") ? P.at("m") : 3.0) * dx;
  return pd::lattice_family_size(delta / dx, sc.simulation.dimension == Dimension::ThreeD ? 3 : 2);
}

/// A bond takes only a solid's elastic moduli (probe_moduli): a model whose plasticity, EOS or
/// failure criterion the bonds would drop is refused, not run as another material. Micro-plastic
/// bonds and bond failure are the peridynamics section's (yield_stress, critical_stretch).
void check_bond_materials(const Scenario& sc) {
  for (const MaterialSpec& m : sc.materials) {
    if (m.model == "explosive") continue;  // a peridynamic gas: its pressure is the model's
    auto at = [&](const std::string& key) {
      const auto it = m.param_marks.find(key);
      return it != m.param_marks.end() ? it->second : m.mark;
    };
    auto refuse = [&](const DeckMark& mark, const std::string& key, const std::string& what) {
      throw DeckError(mark.file, mark.line, mark.column, m.mark.key_path + "." + key,
                      "material '" + m.name + "': " + what +
                          "; peridynamic bonds take only the elastic moduli (bulk and shear) of a material, so the rest "
                          "would be dropped: use model linear_elastic, with peridynamics.yield_stress for "
                          "micro-plastic bonds and critical_stretch or fracture_energy for their failure");
    };
    if (m.model != "linear_elastic") refuse(at("model"), "model", "model '" + m.model + "' is not elastic");
    const auto crit = m.params.choices.find("failure.criterion");
    if (crit != m.params.choices.end() && crit->second != "none")
      refuse(at("failure.criterion"), "failure.criterion", "failure.criterion '" + crit->second + "' is a point's");
    const auto eos = m.params.choices.find("eos.type");
    if (eos != m.params.choices.end() && eos->second != "linear")
      refuse(at("eos.type"), "eos.type", "eos.type '" + eos->second + "' is not linear");
  }
}

/// The deck's horizon, checked before anything is seeded (a family as large as the body would
/// cost its memory first): at least the lattice spacing, and, when it spans more than ten
/// spacings, at most twice every solid body's largest extent; beyond that every point's family
/// holds the whole body and its bonds cannot localise damage (beyond half of it, a warning: a
/// test body of a few points at m = 3 is legal; the explosive's gas horizon scales with its own
/// lattice). The bonds' materials too
/// (check_bond_materials).
const Scenario& checked_for_bonds(const Scenario& sc) {
  check_bond_materials(sc);
  const ParamValues& P = sc.solver_params;
  const bool m_given = P.given("m"), h_given = P.given("horizon");
  if (m_given && h_given) section_error(sc, "horizon", "give the horizon or m (horizon = m x lattice spacing), not both");
  const double dx = sc.grid.cell_size;
  const double delta = h_given ? P.at("horizon") : (m_given ? P.at("m") : 3.0) * dx;
  const std::string key = h_given ? "horizon" : "m";
  if (!(delta >= dx))
    section_error(sc, key,
                  fmt::format("the horizon {:g} m must be at least the lattice spacing grid.cell_size = {:g} m", delta, dx));
  const int nd = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  for (const BodySpec& b : sc.bodies) {
    const MaterialSpec* m = nullptr;
    for (const MaterialSpec& ms : sc.materials)
      if (ms.name == b.material) m = &ms;
    if (m && m->model == "explosive") continue;
    Vec3 lo, hi;
    shape_bounds(b.shape, nd, lo, hi);
    double extent = 0.0;
    for (int k = 0; k < nd; ++k) extent = std::max(extent, hi[k] - lo[k]);
    const std::string why = fmt::format(
        "the horizon {:g} m is {} the largest extent of body '{}' ({:g} m): each point's family holds most of the "
        "body, and its bonds cannot localise damage; use a horizon of a few lattice spacings (peridynamics.m, "
        "default 3) or a finer lattice",
        delta, delta > 2.0 * extent ? "more than twice" : "more than half", b.name, extent);
    if (delta > 2.0 * extent && delta > 10.0 * dx) section_error(sc, key, why);
    if (2.0 * delta > extent) spdlog::warn("{}", why);
  }
  return sc;
}

}  // namespace

ProbedModuli probe_moduli(const Material& material) {
  // One point, driven by a volumetric and then (from the start again) a shear velocity gradient
  // over dt = 1 s: for any model, at the reference state and for an increment of 1e-7 far inside
  // the elastic range, sigma = K tr(eps) I + 2 G dev(eps) to O(1e-7).
  constexpr double e = 1e-7;
  auto drive = [&](const Mat3& L) {
    FieldStore s;
    declare_point_fields(s);
    material.declare_fields(s);
    s.resize(1);
    material.initialise_state(s, 0, 1);
    s.real("mass")[0] = material.density();
    s.real("volume0")[0] = 1.0;
    s.real("volume")[0] = 1.0;
    s.view<Mat3>("R")[0] = Mat3::identity();
    Mat3& F = s.view<Mat3>("F")[0];
    F = (Mat3::identity() + L) * Mat3::identity();
    s.view<Mat3>("L")[0] = L;
    static const Index kPoint[1] = {0};
    material.update(make_batch(s, kPoint, 1, 1.0, false));
    return s.view<Mat3>("stress")[0];
  };
  // The adapter's midpoint increment of G = dt L is D dt = sym(G (I + G/2)^-1) (strain_increment.hpp).
  const double eps_vol = e / (1.0 + 0.5 * e);
  const Mat3 sv = drive(Mat3::diag(e, e, e));
  Mat3 shear;
  shear(0, 1) = shear(1, 0) = e;
  const Mat3 ss = drive(shear);
  ProbedModuli m;
  m.bulk = (sv(0, 0) + sv(1, 1) + sv(2, 2)) / (9.0 * eps_vol);
  m.shear = ss(0, 1) / (2.0 * e);
  return m;
}

PdSolver::PdSolver(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, Communicator comm)
    : scenario_(checked_for_bonds(sc)),
      comm_(comm),
      // Every body on the lattice of spacing grid.cell_size (one point per cell); each point holds
      // its family's bond ends (m = 3 in 3D: 122 of kSolverBytesPerBond).
      pts_(sc, std::move(materials), SeedLattice{sc.grid, 1, full_family_size(sc) * kSolverBytesPerBond}, 0.0,
           fmt::format("families of {:g} bond ends per point, set by peridynamics.m or horizon", full_family_size(sc)),
           comm),
      points_(pts_.store()) {
  const ParamValues& P = sc.solver_params;
  // Explosives are a peridynamic gas (gas_pass.hpp): a pressure from the material library, no
  // bond stiffness. The products' pressure of a plane-stress plate has no meaning.
  if (const MaterialSpec* m = first_material_of_model(sc, "explosive"); m && sc.simulation.plane_stress)
    throw DeckError(m->mark.file, m->mark.line, m->mark.column, m->mark.key_path + ".model",
                    "an explosive (a peridynamic gas) needs dimension 3d or plane_strain, not plane_stress");
  dx_ = sc.grid.cell_size;
  delta_ = P.given("horizon") ? P.at("horizon") : (P.given("m") ? P.at("m") : 3.0) * dx_;  // checked before seeding
  if (P.given("critical_stretch") && P.given("fracture_energy"))
    section_error(sc, "fracture_energy", "give critical_stretch or fracture_energy, not both");
  alpha_ = P.at("stretch_alpha");
  fragment_interval_ = P.at("fragment_interval");
  contact_on_ = P.choices.at("contact") == "on";
  contact_all_pairs_ = P.choices.at("contact_pairs") == "all";
  lammps_break_ = P.choices.at("break_rule") == "lammps";
  fragment_threshold_ = P.given("fragment_damage_threshold") ? P.at("fragment_damage_threshold") : 2.0;
  next_fragment_time_ = fragment_interval_ > 0.0 ? fragment_interval_ : kInf;
  dt_safety_ = P.at("dt_safety");
  damping_ = sc.simulation.damping;
  dim_ = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  thickness_ = dim_ == 2 && P.given("thickness") ? P.at("thickness") : 1.0;
  if (dim_ == 3 && P.given("thickness"))
    section_error(sc, "thickness", "a thickness belongs to 2D runs (dimension: plane_stress or plane_strain)");
  if (pts_.pending() > 0)
    section_error(sc, "", "bodies with a later activation (activation_time, activation_stage, rods, jets) are not "
                          "supported by the peridynamics solver yet: their bonds would have to be built on arrival");
  if (sc.simulation.on_particle_exit != "stop")
    section_error(sc, "", "simulation.on_particle_exit: delete is not supported by the peridynamics solver yet");

  // Bond constants per material pair: c = 18 K/(pi delta^4) (Silling & Askari 2005 eq. 22) for each
  // material, two materials' bond as their two half-bonds in series (harmonic mean); the critical
  // stretch of a mixed bond is the smaller one.
  const auto& mats = pts_.materials();
  nmat_ = static_cast<int>(mats.size());
  const bool correct = P.choices.at("volume_correction") == "partial";
  const bool lattice = P.choices.at("calibration") == "lattice";
  const pd::LatticeMoments moments = pd::lattice_moments(delta_, dx_, correct, dim_);
  // Continuum moments: 3D m1 = pi delta^4, m2 = pi delta^5/5; 2D (unit thickness) m1 = 2 pi delta^3/3,
  // m2 = delta^4/2 (Ha & Bobaru, Int. J. Fract. 162 (2010) 229: c = 9E/(pi h delta^3) in plane stress).
  const double m1 = lattice ? moments.m1 : (dim_ == 3 ? std::numbers::pi * std::pow(delta_, 4)
                                                      : 2.0 * std::numbers::pi * std::pow(delta_, 3) / 3.0);
  const double m2 = lattice ? moments.m2 : (dim_ == 3 ? std::numbers::pi * std::pow(delta_, 5) / 5.0
                                                      : std::pow(delta_, 4) / 2.0);
  // The dilatational modulus of each material in the model's dimension: K in 3D, the in-plane bulk
  // modulus K2 in 2D (K + G/3 in plane strain, E/(2(1 - nu)) in plane stress).
  std::vector<double> kd(nmat_), c(nmat_), s0(nmat_);
  gas_material_.assign(static_cast<size_t>(nmat_), 0);
  for (int a = 0; a < nmat_; ++a) gas_material_[a] = std::string(mats[a]->model()) == "explosive";
  // Bonds carry the solids' forces: their points keep F = I and zero stress, which the output and
  // the failure diagnostics would show as if they were measured. The gas (an explosive) is fed F
  // and has a pressure, so those two stay when it is present; the rotation, velocity gradient and
  // MPM's particle half-size never mean anything here.
  const bool gas = std::find(gas_material_.begin(), gas_material_.end(), 1) != gas_material_.end();
  for (const char* name : {"R", "L", "half_size"}) points_.set_output(name, false);
  if (!gas)
    for (const char* name : {"F", "stress"}) points_.set_output(name, false);
  if (sc.output.domains)
    throw DeckError(sc.file, 0, 0, "output.domains",
                    "peridynamic points have no deforming domain to draw (their bonds carry no F): set output.domains "
                    "to false");
  // Bodies on their own, coarser lattice (bodies[].point_spacing): only the products. A solid's
  // bonds are calibrated on the lattice of grid.cell_size (lattice_moments); the gas is a pressure
  // whose measure X is a normalised average over whatever family it has, so a coarser gas lattice
  // scales its horizon with its spacing (build_gas_family) and keeps every relation.
  body_scale_.assign(sc.bodies.size(), 1.0);
  for (size_t b = 0; b < sc.bodies.size(); ++b) {
    const BodySpec& body = sc.bodies[b];
    if (!(body.point_spacing > 0.0)) continue;
    auto fail = [&](const std::string& what) {
      throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path + ".point_spacing", what);
    };
    bool gas = false;
    for (int a = 0; a < nmat_; ++a) gas = gas || (mats[a]->name() == body.material && gas_material_[a]);
    if (!gas)
      fail("only an explosive body (the products, a peridynamic gas) may take its own lattice spacing: a solid's "
           "bonds are calibrated on grid.cell_size = " + fmt::format("{:g}", dx_) + " m");
    if (body.point_spacing < dx_ * (1.0 - 1e-12))
      fail(fmt::format("expected at least grid.cell_size = {:g} m (the products may be coarser than the case, not finer), "
                       "got {:g} m", dx_, body.point_spacing));
    body_scale_[b] = std::max(1.0, body.point_spacing / dx_);
    max_scale_ = std::max(max_scale_, body_scale_[b]);
  }
  for (int a = 0; a < nmat_; ++a) {
    if (gas_material_[a]) continue;  // no bonds: its stiffness is its pressure (gas_pass.hpp)
    const ProbedModuli mod = probe_moduli(*mats[a]);
    if (!(mod.bulk > 0.0) || !std::isfinite(mod.bulk))
      throw DeckError(sc.file, 0, 0, "materials." + mats[a]->name(),
                      fmt::format("peridynamics needs a positive bulk modulus; material '{}' gives {:g} Pa",
                                  mats[a]->name(), mod.bulk));
    kd[a] = mod.bulk;
    if (dim_ == 2) {
      const double E = 9.0 * mod.bulk * mod.shear / (3.0 * mod.bulk + mod.shear);
      const double nu = (3.0 * mod.bulk - 2.0 * mod.shear) / (2.0 * (3.0 * mod.bulk + mod.shear));
      kd[a] = sc.simulation.plane_stress ? E / (2.0 * (1.0 - nu)) : mod.bulk + mod.shear / 3.0;
    }
  }
  m1_ = m1;
  for (int a = 0; a < nmat_; ++a) {
    // continuum: c = 18 K/(pi delta^4) (S&A 2005 eq. 22), s00 = sqrt(5 G0/(9 K delta)) (eq. 25), exact
    // for the integral over the horizon sphere; on the lattice the sums differ (K_PD = 0.90 K and
    // G = 0.87 G0 at m = 3 with partial volumes), so `lattice` takes the same two relations over the
    // lattice family of an interior point: c = 18 K/m1, s00 = sqrt(2 G0/(c m2)) (bond_family.hpp).
    // The energy density of a dilatation eps is W = c eps^2 m1 / 4 for any dimension (S&A 2005 eq. 21
    // summed over the family); it equals the continuum 9 K eps^2/2 in 3D and 2 K2 eps^2 in 2D (eps in
    // both in-plane directions). So c = 18 K/m1 (3D) or 8 K2/m1 (2D). A crack opening through its
    // critical stretch releases G = c s0^2 m2/2, so s00 = sqrt(2 G0/(c m2)) (eq. 25 in 3D with the
    // continuum m2).
    c[a] = (dim_ == 3 ? 18.0 * kd[a] : 8.0 * kd[a]) / m1;
    if (P.given("critical_stretch"))
      s0[a] = P.at("critical_stretch");
    else if (P.given("fracture_energy"))
      s0[a] = std::sqrt(2.0 * P.at("fracture_energy") / (c[a] * m2));
    else
      s0[a] = kInf;
  }
  // Micro-plastic bonds: first yield of the most stretched bond (the one along the load) under
  // uniaxial stress sigma_y, s_y = sigma_y/E_PD with the modulus of the bond-based model (nu = 1/4 in
  // 3D: E = 3K/2; in 2D E = 4 K2/3 for plane stress, nu = 1/3, and plane strain alike). With several
  // materials the smallest modulus sets it (one yield stretch for every bond).
  if (P.given("yield_stress")) {
    double e_min = kInf;
    for (int a = 0; a < nmat_; ++a)
      if (!gas_material_[a]) e_min = std::min(e_min, dim_ == 3 ? 1.5 * kd[a] : 4.0 / 3.0 * kd[a]);
    yield_stretch_ = P.at("yield_stress") / e_min;
  }
  c_.resize(static_cast<size_t>(nmat_ * nmat_));
  c_contact_.resize(c_.size());
  s00_.resize(c_.size());
  for (int a = 0; a < nmat_; ++a)
    for (int b = 0; b < nmat_; ++b) {
      // A gas takes no bond stiffness, and none in the contact springs either (they scale with c).
      const bool gas = gas_material_[a] || gas_material_[b];
      c_[a * nmat_ + b] = gas ? 0.0 : 2.0 * c[a] * c[b] / (c[a] + c[b]);
      s00_[a * nmat_ + b] = gas ? kInf : std::min(s0[a], s0[b]);
      // Products meeting a solid they were not bonded to (gas streaming towards the case from
      // deep inside the charge) are stopped by the solid's contact springs; gas-gas pairs have none.
      c_contact_[a * nmat_ + b] = gas_material_[a] && gas_material_[b] ? 0.0
                                  : gas_material_[a]                  ? c[b]
                                  : gas_material_[b]                  ? c[a]
                                                                      : c_[a * nmat_ + b];
    }

  // Fields of this solver: damage (output) and the acceleration of the last force evaluation.
  points_.add_real("damage", 1, "1");
  points_.add_real("pd_accel", 3, "m/s^2", false);
  const auto build_start = std::chrono::steady_clock::now();
  build_local_points(correct);
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
  if (const double every = P.at("gas_refamily_steps"); every > 0.0) {
    if (every != std::floor(every)) section_error(sc, "gas_refamily_steps", "expected a whole number of steps");
    // The renewed family needs every neighbour within the current horizon, which another rank's
    // points may be: one rank only so far (docs/parallel.md).
    if (has_gas_ && comm_.distributed())
      section_error(sc, "gas_refamily_steps",
                    "renewing the gas family runs on one MPI rank only so far (" + std::to_string(comm_.size()) +
                        " ranks were started; set it to 0 or run on one rank)");
    gas_refamily_every_ = static_cast<int>(every);
  }
  s0_.assign(static_cast<size_t>(nl), kInf);
  const auto* mat = local_.material.data();
  for (Index p = 0; p < nb; ++p) {
    double s = kInf;
    for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k)
      s = std::min(s, s00_[mat[p] * nmat_ + mat[bonds_.other[k]]]);
    s0_[p] = s;  // the first step breaks at s00 (no previous stretch yet)
  }
  // Scatter of the critical stretch (stretch_scatter): s00 of each point times 1 + sigma z, z a
  // standard normal drawn from the point's id (splitmix64 + Box-Muller: the same for any thread
  // count, rank count or run), truncated to [1 - 3 sigma, 1 + 3 sigma]. A flawless lattice breaks
  // with its own symmetry (an expanding ring into identical fragments); real materials carry flaws
  // (Grady 2006 ch. 2). The smaller s0 of a bond's two ends still decides.
  if (const double sigma = P.at("stretch_scatter"); sigma > 0.0) {
    const auto* id = local_.id.data();
    auto mix = [](std::uint64_t z) {
      z += 0x9e3779b97f4a7c15ULL;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      return z ^ (z >> 31);
    };
    for (Index p = 0; p < nb; ++p) {
      const std::uint64_t h1 = mix(static_cast<std::uint64_t>(id[p]) * 2 + 1), h2 = mix(h1);
      const double u1 = (static_cast<double>(h1 >> 11) + 0.5) / 9007199254740992.0;  // (0, 1)
      const double u2 = static_cast<double>(h2 >> 11) / 9007199254740992.0;
      const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
      s0_[p] *= 1.0 + sigma * std::clamp(z, -3.0, 3.0);
    }
  }
  halo_.update_bond_values(comm_, local_, s0_);  // a ghost's row is partial: its s0 is its owner's
  s00_point_ = s0_;
  if (std::isfinite(yield_stretch_)) sp_.assign(bonds_.other.size(), 0.0);
  dissipated_.assign(static_cast<size_t>(nl), 0.0);
  contact_energy_.assign(static_cast<size_t>(nl), 0.0);
  contact_.skin = P.at("contact_skin") * dx_;
  const auto* vol0 = local_.vol0.data();
  // The damage denominator of each point, sum_j beta V_j, and for the half-bond force pass (each
  // bond evaluated once, from its lower-index end): where each row's upper part starts, where each
  // bond sits in its other end's row, and the blocks of points (compute_forces).
  vol_all_.assign(static_cast<size_t>(nb), 0.0);
  upper_.assign(static_cast<size_t>(nb), 0);
  mirror_.assign(bonds_.other.size(), 0);
  inv_len0_.resize(bonds_.other.size());
  for_each(0, static_cast<Index>(inv_len0_.size()), [&](Index k) { inv_len0_[k] = 1.0 / bonds_.length0[k]; });
  for_each(0, nb, [&](Index p) {
    double va = 0.0;
    const Index k0 = bonds_.offset[p], k1 = bonds_.offset[p + 1];
    for (Index k = k0; k < k1; ++k) {
      const Index q = bonds_.other[k];
      va += bonds_.volume_factor[k] * vol0[q];
      // Rows are sorted by neighbour index: p's place in q's row by binary search.
      const auto* row = bonds_.other.data() + bonds_.offset[q];
      const auto* end = bonds_.other.data() + bonds_.offset[q + 1];
      mirror_[k] = static_cast<std::int32_t>(std::lower_bound(row, end, static_cast<std::int32_t>(p)) - row);
    }
    vol_all_[p] = va > 0.0 ? va : 1.0;  // a point without bonds has no damage
    upper_[p] = std::upper_bound(bonds_.other.data() + k0, bonds_.other.data() + k1, static_cast<std::int32_t>(p)) -
                bonds_.other.data();
  });
  // Blocks of the half-bond pass over ids: block b holds ids [bB, (b + 1)B), B at least the largest
  // id span of a bond (a bond of block b ends in b or b + 1) and at least 64 blocks when the points
  // allow (so that two phases keep every thread busy). A function of the bonds only, so on several
  // ranks each own point receives its bonds' contributions in the serial order.
  {
    const auto* id = local_.id.data();
    std::int64_t span = 1, top = 0;
    for (Index p = 0; p < nb; ++p) {
      top = std::max(top, id[p] + 1);
      if (bonds_.offset[p + 1] > bonds_.offset[p]) span = std::max(span, id[bonds_.other[bonds_.offset[p + 1] - 1]] - id[p]);
    }
    span = comm_.max(span);
    top = comm_.max(top);
    const std::int64_t block = std::max<std::int64_t>(span, (global_points_ + 63) / 64);
    block_start_.clear();
    Index l = 0;
    for (std::int64_t b = 0; b < top; b += block) {
      while (l < nb && id[l] < b) ++l;
      block_start_.push_back(l);
    }
    block_start_.push_back(nb);
  }
  bond_build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - build_start).count();
  stiff_bond_.assign(static_cast<size_t>(nb), 0.0);
  stiff_contact_.assign(static_cast<size_t>(nl), 0.0);
  x_prev_ = local_.x;
  // Surface correction (surface_correction: energy; Madenci & Oterkus 2014 §4.2, reviewed by Le &
  // Bobaru, Comput. Mech. 61 (2018) 499): a point near a free surface misses part of its family and
  // is softer; under a uniform dilatation its energy density is c eps^2 m1_p / 4 instead of the
  // interior c eps^2 m1 / 4, so its factor is lambda_p = m1 / m1_p, and a bond is stiffened by the
  // mean of its two ends' factors (forces and energies; the critical stretch is left as it is).
  if (P.choices.at("surface_correction") == "energy") {
    surface_factor_.assign(static_cast<size_t>(nb), 1.0);
    for_each(0, nb, [&](Index p) {
      double m1p = 0.0;
      for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k)
        m1p += bonds_.length0[k] * bonds_.volume_factor[k] * vol0[bonds_.other[k]];
      if (m1p > 0.0) surface_factor_[p] = moments.m1 / m1p;
    });
    halo_.update_bond_values(comm_, local_, surface_factor_);
  }
  // Stable step of each point (Silling & Askari 2005 eq. 17): dt < sqrt(2 rho / sum_j V_j c/|xi|).
  for_each(0, nb, [&](Index p) {
    double sum = 0.0;
    for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k) {
      const Index q = bonds_.other[k];
      const double g = surface_factor_.empty() ? 1.0 : 0.5 * (surface_factor_[p] + surface_factor_[q]);
      sum += g * vol0[q] * bonds_.volume_factor[k] * c_[mat[p] * nmat_ + mat[q]] / bonds_.length0[k];
    }
    stiff_bond_[p] = sum;
  });
  // Pre-cracks (deck `cracks`): bonds whose ends lie on either side of the segment, in the x-y plane.
  const auto* bid = local_.body.data();
  const auto* x0 = local_.x0.data();
  for (const CrackSpec& crack : sc.cracks) {
    const int body = crack.body.empty() ? -1 : body_index(sc, crack.body);
    const Vec3 a = crack.from, b = crack.to;
    // Which side of the line o-e the point c is on, in the x-y plane: +1 left, -1 right, 0 on it
    // (within 1e-9 of the length o-e, so that round-off never decides a point on the line).
    auto side = [](const Vec3& o, const Vec3& e, const Vec3& c) {
      const double len = std::hypot(e[0] - o[0], e[1] - o[1]);
      const double d = ((e[0] - o[0]) * (c[1] - o[1]) - (e[1] - o[1]) * (c[0] - o[0])) / len;
      return std::abs(d) <= 1e-9 * len ? 0 : (d > 0.0 ? 1 : -1);
    };
    const Index cut = cut_bonds([&](Index p, Index q) {
      if (body >= 0 && bid[p] != body) return false;  // bonds join points of one body only
      const Vec3 &xp = x0[p], &xq = x0[q];
      if (xp[0] == xq[0] && xp[1] == xq[1]) return false;  // a bond along z crosses no x-y segment
      // Crossing of the segments p-q and a-b: p and q on either side of the crack line (a point on
      // it counts as left), a and b strictly on either side of the bond's line; both tests read
      // the same from either end, so a bond is cut at both ends or neither.
      const bool pq = (side(a, b, xp) >= 0) != (side(a, b, xq) >= 0);
      return pq && side(xp, xq, a) * side(xp, xq, b) < 0;
    });
    if (cut == 0)
      throw DeckError(crack.mark.file, crack.mark.line, crack.mark.column, crack.mark.key_path,
                      "this crack cuts no bond: check that the segment crosses the body (x-y plane)");
  }
  sync_local();
  x_prev_ = local_.x;
  if (contact_on_) rebuild_contacts();
  compute_forces();
}

void PdSolver::build_local_points(bool correct) {
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
  bonds_ = pd::build_bond_family(cx0.data(), nc, delta_, correct ? dx_ : 0.0, dim_, cbody.data(), cgas.data());
  // Detonation products: the gas family (every pair within the horizon with a gas end, gas_pass.hpp).
  const bool any_gas = std::find(gas_material_.begin(), gas_material_.end(), 1) != gas_material_.end();
  if (any_gas) {
    std::vector<double> cscale(static_cast<size_t>(nc), 1.0);
    for (Index c = 0; c < nc; ++c) cscale[c] = cgas[c] ? body_scale_[cbody[c]] : 1.0;
    gas_bonds_ = pd::build_gas_family(cx0.data(), nc, delta_, correct ? dx_ : 0.0, dim_, cgas.data(),
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
  const auto* vol0 = points_.real("volume0");
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
  const auto* vol0 = points_.real("volume0");
  const auto* mass = points_.real("mass");
  const Index* own = local_.own.data();
  double dt = kInf;
#pragma omp parallel for schedule(static) reduction(min : dt) if (n > kParallelThreshold)
  for (Index p = 0; p < n; ++p) {
    const Index l = own[p];
    const double sum = stiff_bond_[l] + stiff_contact_[l];
    if (sum > 0.0) dt = std::min(dt, std::sqrt(2.0 * mass[p] / vol0[p] / sum));
  }
  if (has_gas_) dt = std::min(dt, gas_stable_dt());
  dt = comm_.min(dt_safety_ * dt);
  if (!std::isfinite(dt)) dt = scenario_.simulation.end_time;  // no bonds at all: free flight
  if (scenario_.simulation.max_dt > 0.0) dt = std::min(dt, scenario_.simulation.max_dt);
  return dt;
}

void PdSolver::compute_forces() {
  // Over the local points (own and ghosts, local_.x current: sync_local); results to own points.
  const Index n = points_.size(), nl = local_.size();
  const auto* x = local_.x.data();
  const auto* vol0 = local_.vol0.data();
  const auto* mass = points_.real("mass");
  const auto* mat = local_.material.data();
  const Index* own = local_.own.data();
  auto* acc = points_.view<Vec3>("pd_accel");
  auto* damage = points_.real("damage");
  auto* eint = points_.real("internal_energy");
  auto* wdis = points_.real("plastic_work");
  const double* s0 = s0_.data();
  const double* len0 = bonds_.length0.data();
  const float* beta = bonds_.volume_factor.data();
  const std::int32_t* other = bonds_.other.data();
  const std::int32_t* mirror = mirror_.data();
  std::uint8_t* broken = bonds_.broken.data();
  const double alpha = alpha_;
  const bool plastic = !sp_.empty();
  double* sp = sp_.data();
  const double sy = yield_stretch_;
  const Vec3* xprev = x_prev_.data();  // positions at the step's start (= x outside a step)
  // Short-range contact (contact_list.hpp): c_s = 15 c / delta per unit volume squared and unit
  // overlap (Silling & Askari 2005; LAMMPS pair_peri_pmb), reach d = min(0.9 |xi|, 1.35 dx).
  const bool contact = contact_on_;
  const bool bonded_contact = contact && contact_all_pairs_;
  const double cs_over_c = 15.0 / delta_, range = 1.35 * dx_;
  // Per-point sums of this evaluation (each bond adds to both of its ends).
  Acc& A = acc_;
  A.resize(nl);
  for_each(0, nl, [&](Index p) { A.clear(p); });

  if (nl == 0) return;
  pd::BondPassArgs args{x[0].v,   vol0,       mat,        c_.data(),  nmat_,   s0,          len0, inv_len0_.data(), beta,
                        other,     mirror,     broken,     bonds_.offset.data(),  upper_.data(), plastic ? sp : nullptr,
                        sy,        alpha,      contact,    bonded_contact,        cs_over_c, range, xprev[0].v,
                        A.f[0].v,  A.energy.data(), A.dis.data(), A.vol_broken.data(), A.smx.data(),
                        A.e_contact.data(), A.k_contact.data(),
                        surface_factor_.empty() ? nullptr : surface_factor_.data(), lammps_break_};
  const Index nblock = static_cast<Index>(block_start_.size()) - 1;
  for (int phase = 0; phase < 2; ++phase) {
    const Index nphase = (nblock - phase + 1) / 2;
#pragma omp parallel for schedule(dynamic, 1) if (nphase > 1 && n > kParallelThreshold)
    for (Index j = 0; j < nphase; ++j) {
      const Index b = 2 * j + phase;
      pd::bond_pass(args, block_start_[b], block_start_[b + 1]);
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
  std::exception_ptr failure;
  try {
    advance(dt);
  } catch (const std::exception&) {
    failure = std::current_exception();
  }
  rethrow_agreed(comm_, failure);
}

void PdSolver::advance(double dt) {
  // Velocity Verlet (Silling & Askari 2005 §4 use the explicit central difference; Verlet is the
  // same scheme with synchronised velocities): v_{n+1/2} = v_n + dt/2 a_n, x_{n+1} = x_n + dt
  // v_{n+1/2}, a_{n+1} from the bonds at x_{n+1}, v_{n+1} = v_{n+1/2} + dt/2 a_{n+1}. External
  // forces enter a with the loads of the step's start and end.
  const Index n = points_.size();
  auto* x = points_.view<Vec3>("x");
  auto* v = points_.view<Vec3>("v");
  const auto* mass = points_.real("mass");
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
  if (contact_on_ && contacts_stale()) rebuild_contacts();
  compute_forces();
  time_ += dt;
  ++steps_;
  if (time_ >= next_fragment_time_ * (1.0 - 1e-12)) {
    auto rows = fragment_rows(fragments());
    fragment_rows_.insert(fragment_rows_.end(), rows.begin(), rows.end());
    while (next_fragment_time_ <= time_ * (1.0 + 1e-12)) next_fragment_time_ += fragment_interval_;
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
  const auto* damage = points_.real("damage");
  for (Index p = 0; p < points_.size(); ++p) dmax = std::max(dmax, damage[p]);
  dmax = comm_.max(dmax);
  const double broken = static_cast<double>(broken_bonds());
  std::int64_t gas_bonds = 0;  // each counted at both ends, at own points
  if (has_gas_)
    for (Index l : local_.own) gas_bonds += gas_bonds_.offset[l + 1] - gas_bonds_.offset[l];
  gas_bonds = comm_.sum(gas_bonds);
  std::vector<std::pair<std::string, double>> out{{"broken_bonds", broken},
          {"fragment_count", static_cast<double>(frags.size())},
          {"largest_fragment_mass", frags.empty() ? 0.0 : thickness_ * frags.front().mass},
          {"mean_fragment_mass", frags.empty() ? 0.0 : thickness_ * total / static_cast<double>(frags.size())},
          {"max_damage", dmax},
          // Cost figures (docs/performance.md): the bond families with their solver arrays, the
          // contact list rebuilds, and the storage per bond end.
          {"contact_list_builds", static_cast<double>(contact_.builds)},
          {"bytes_per_bond_end", kSolverBytesPerBond + (sp_.empty() ? 0.0 : sizeof(double))},
          {"gas_bonds", static_cast<double>(gas_bonds) / 2.0},
          {"vented_gas_points", static_cast<double>(comm_.sum(static_cast<std::int64_t>(vented_count_)))},
          {"gas_rate_limited_steps", static_cast<double>(comm_.sum(static_cast<std::int64_t>(gas_rate_limited_)))},
          {"gas_family_renewals", static_cast<double>(gas_renewals_)}};
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
  if (!comm_.distributed()) return pd::find_fragments(bonds_, points_, fragment_threshold_, skip_gas());
  return pd::find_fragments_gathered(comm_, bonds_, local_.own, local_.id.data(), points_, fragment_threshold_,
                                     gas_material_);
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
  if (!sp_.empty()) s += fmt::format("#   yield_stretch: {:.10g}   # micro-plastic bonds\n", yield_stretch_);
  const auto& mats = pts_.materials();
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
  const auto* damage = points_.real("damage");
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

/// An optional word parameter: one of `choices`, the first the default.

std::vector<ParamSpec> pd_params() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ParamSpec m{"m", "1", "horizon over lattice spacing (default 3; give m or horizon)", false, nan, 1.0, 20.0};
  ParamSpec horizon{"horizon", "m", "horizon delta (instead of m)", false, nan, 0.0, kInf, true};
  const ParamSpec vc =
      word_param("volume_correction", "partial-volume correction of neighbours cut by the horizon", {"partial", "none"});
  ParamSpec s0{"critical_stretch", "1", "bond critical stretch s00 (or fracture_energy; neither: no failure)", false,
               nan, 0.0, kInf, true};
  ParamSpec g0{"fracture_energy", "J/m^2",
               "fracture energy G0: s00 = sqrt(2 G0/(c m2)) (continuum m2: S&A 2005 eq. 25, sqrt(5 G0/(9 K delta)))",
               false, nan, 0.0, kInf,
               true};
  ParamSpec alpha{"stretch_alpha", "1", "s0 = s00 - alpha s_min (LAMMPS PERI)", false, 0.0, 0.0, kInf};
  ParamSpec safety{"dt_safety", "1", "fraction of the Silling-Askari stable time step", false, 0.8, 0.0, 1.0, true};
  ParamSpec scatter{"stretch_scatter", "1",
                     "relative standard deviation of each point's critical stretch (flaws; 0: a perfect lattice)", false,
                     0.0, 0.0, 0.3};
  ParamSpec fint{"fragment_interval", "s", "time between fragment snapshots in fragments.csv (0: at the end only)",
                 false, 0.0, 0.0, kInf};
  ParamSpec fthr{"fragment_damage_threshold", "1",
                 "points with more damage are left out of the fragments (dust); default: none left out", false, nan,
                 0.0, 1.0};
  // At most 1 km: beyond, the totals (mass, energies per plate) overflow before the run ends.
  ParamSpec thick{"thickness", "m", "2D runs: the plate thickness (totals are per this thickness; default 1 m)", false,
                  nan, 0.0, 1.0e3, true};
  ParamSpec yield{"yield_stress", "Pa",
                  "micro-plastic bonds: uniaxial yield stress (bond yield stretch s_y = yield_stress / E_PD); "
                  "absent: micro-elastic bonds",
                  false, nan, 0.0, kInf, true};
  const ParamSpec cal = word_param(
      "calibration",
      "bond constants from the continuum integrals (S&A 2005) or from the lattice family (exact K and G0 "
      "for interior points)",
      {"lattice", "continuum"});
  const ParamSpec surf = word_param(
      "surface_correction",
      "none, or energy: bonds near free surfaces stiffened by the mean of their ends' factors m1/m1_p "
      "(Madenci & Oterkus 2014; Le & Bobaru 2018)",
      {"none", "energy"});
  const ParamSpec contact =
      word_param("contact", "short-range contact forces between points not bonded (S&A 2005, LAMMPS PERI)", {"on", "off"});
  const ParamSpec pairs = word_param(
      "contact_pairs",
      "unbonded: contact between points not bonded (S&A 2005); all: intact bonds compressed below "
      "0.9 |xi| repel too (LAMMPS PERI)",
      {"unbonded", "all"});
  const ParamSpec rule = word_param(
      "break_rule",
      "work: a breaking bond stops acting and dissipates its trapezoidal work over the step (energy "
      "conserving); lammps: it acts once more and dissipates U(s) (LAMMPS PERI's order, for comparisons)",
      {"work", "lammps"});
  ParamSpec refam{"gas_refamily_steps", "1",
                   "detonation products: steps between renewals of the gas family in the current configuration "
                   "(0: the reference family throughout; pd_gas.cpp)",
                   false, 0.0, 0.0, 1.0e6};
  ParamSpec skin{"contact_skin", "1", "contact list skin over the lattice spacing (rebuilt after skin/2 of motion)",
                 false, 0.5, 0.0, 10.0, true};
  return {m, horizon, vc, thick, cal, surf, yield, s0, g0, alpha, scatter, safety, fint, fthr, contact, pairs, rule, skin, refam};
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
    .pre_cracks = true})
