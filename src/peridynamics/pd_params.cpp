// The deck's peridynamics.* parameters: their specs (names, units, defaults, ranges; docs/deck.md),
// the section read once into PdParams, and the checks the specs cannot express (the horizon against
// the lattice and the bodies, keys that exclude each other, the bonds' materials).
#include "peridynamics/pd_params.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "geometry/shape.hpp"
#include "peridynamics/bond_constants.hpp"
#include "peridynamics/bond_family.hpp"
#include "points/solver_registry.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

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
      throw DeckError(
          mark.file, mark.line, mark.column, m.mark.key_path + "." + key,
          "material '" + m.name + "': " + what +
              "; peridynamic bonds take only the elastic moduli (bulk and shear) of a material, so "
              "the rest "
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

/// The horizon `delta` (deck key `key`) against the lattice spacing and the solid bodies' extents.
void check_horizon(const Scenario& sc, double delta, const std::string& key) {
  const double dx = sc.grid.cell_size;
  if (!(delta >= dx))
    pd_section_error(
        sc, key,
        fmt::format(
            "the horizon {:g} m must be at least the lattice spacing grid.cell_size = {:g} m",
            delta, dx));
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
    if (delta > 2.0 * extent && delta > 10.0 * dx) pd_section_error(sc, key, why);
    if (2.0 * delta > extent) spdlog::warn("{}", why);
  }
}

/// What the state-based solid (lps_pass.hpp) does not take: its 2D forms (Le, Silling & Bobaru 2014)
/// are not built, and the keys below are defined for bonds alone (its yield_stress is Mitchell's
/// plasticity, lps_pass.hpp).
void check_lps(const Scenario& sc, const PdParams& p) {
  const std::string why = " is defined for bond-based bonds only; formulation: lps is the state-based solid";
  if (sc.simulation.dimension != Dimension::ThreeD)
    pd_section_error(sc, "formulation", "formulation: lps runs in 3D only so far (dimension: 3d)");
  if (p.bond_law_fracture_work) pd_section_error(sc, "fracture_work", "fracture_work: bond_law" + why);
  if (p.surface_correction) pd_section_error(sc, "surface_correction", "surface_correction" + why);
  if (p.lammps_break) pd_section_error(sc, "break_rule", "break_rule: lammps" + why);
  if (p.contact_all_pairs) pd_section_error(sc, "contact_pairs", "contact_pairs: all" + why);
}

}  // namespace

std::vector<ParamSpec> pd_params() {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ParamSpec form = word_param(
      "formulation",
      "bond: bond-based, each bond a spring (PMB or micro-plastic; Poisson's ratio 1/4 in 3D); lps: the linear "
      "peridynamic solid, state-based, the bulk and shear moduli of the material (any Poisson's ratio; Silling et "
      "al. 2007 sec. 15; 3D)",
      {"bond", "lps"});
  ParamSpec m{"m", "1", "horizon over lattice spacing (default 3; give m or horizon)", false, nan, 1.0, 20.0};
  ParamSpec horizon{"horizon", "m", "horizon delta (instead of m)", false, nan, 0.0, kInf, true};
  const ParamSpec vc =
      word_param("volume_correction", "partial-volume correction of neighbours cut by the horizon",
                 {"partial", "none"});
  ParamSpec s0{"critical_stretch", "1", "bond critical stretch s00 (or fracture_energy; neither: no failure)", false,
               nan, 0.0, kInf, true};
  ParamSpec g0{"fracture_energy", "J/m^2",
               "fracture energy G0: s00 = sqrt(2 G0/(c m2)) (continuum m2: S&A 2005 eq. 25, sqrt(5 G0/(9 K delta)))",
               false, nan, 0.0, kInf,
               true};
  const ParamSpec gwork = word_param(
      "fracture_work",
      "which work of a bond the fracture energy equals: elastic, c s00^2 m2 / 2 (the PMB bond's, also for "
      "micro-plastic bonds); bond_law, the work of the bonds' own law to s00 (micro-plastic bonds that yield "
      "first: G0 = c m2 s_y (s00 - s_y/2), so a yielding bond dissipates G0 and no more)",
      {"elastic", "bond_law"});
  ParamSpec alpha{"stretch_alpha", "1", "s0 = s00 - alpha s_min (LAMMPS PERI)", false, 0.0, 0.0, kInf};
  ParamSpec safety{"dt_safety", "1", "fraction of the Silling-Askari stable time step", false, 0.8, 0.0, 1.0, true};
  ParamSpec scatter{
      "stretch_scatter",
      "1",
      "relative standard deviation of each point's critical stretch (flaws; 0: a perfect lattice)",
      false,
      0.0,
      0.0,
      0.3};
  ParamSpec seed{"scatter_seed", "1",
                 "draw of the critical-stretch scatter: another whole number gives another set of flaws with the same "
                 "statistics (the run-to-run scatter of fragments); 0: the default draw",
                 false, nan, 0.0, 4.0e9};
  ParamSpec fint{"fragment_interval", "s", "time between fragment snapshots in fragments.csv (0: at the end only)",
                 false, 0.0, 0.0, kInf};
  ParamSpec fthr{"fragment_damage_threshold", "1",
                 "points with more damage are left out of the fragments (dust); default: none left out", false, nan,
                 0.0, 1.0};
  // At most 1 km: beyond, the totals (mass, energies per plate) overflow before the run ends.
  ParamSpec thick{"thickness", "m", "2D runs: the plate thickness (totals are per this thickness; default 1 m)", false,
                  nan, 0.0, 1.0e3, true};
  ParamSpec yield{"yield_stress", "Pa",
                  "micro-plastic bonds: first yield under uniaxial stress (bond yield stretch s_y = yield_stress / "
                  "E_PD; the solid then flows at 1.83 times it in 3D, 1.41 in 2D: flow_stress gives that plateau); "
                  "with formulation lps, the von Mises yield stress of the state-based plasticity (Mitchell 2011); "
                  "absent: elastic",
                  false, nan, 0.0, kInf, true};
  ParamSpec flow{"flow_stress", "Pa",
                 "micro-plastic bonds: uniaxial flow stress, the plateau of a tensile test (a steel's yield "
                 "stress); s_y = flow_stress / (k E_PD), k = 1.8324 in 3D and 1.4115 in 2D (the bonds' first "
                 "yield is then at flow_stress / k); instead of yield_stress",
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
  const ParamSpec contact = word_param(
      "contact", "short-range contact forces between points not bonded (S&A 2005, LAMMPS PERI)",
      {"on", "off"});
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
  return {form, m,       horizon, vc,   thick, cal,     surf,  yield, flow, s0,   g0,   gwork, alpha,
          scatter, seed,    safety, fint, fthr, contact, pairs, rule, skin,  refam};
}

void pd_section_error(const Scenario& sc, const std::string& key, const std::string& message) {
  throw_solver_param_error(sc, "peridynamics", key, message);
}

double PdParams::full_family_size(const Scenario& sc) const {
  return pd::lattice_family_size(horizon / sc.grid.cell_size, sc.simulation.dimension == Dimension::ThreeD ? 3 : 2);
}

PdParams read_pd_params(const Scenario& sc) {
  check_bond_materials(sc);
  const ParamValues& P = sc.solver_params;
  PdParams p;
  const bool m_given = P.given("m"), h_given = P.given("horizon");
  if (m_given && h_given)
    pd_section_error(sc, "horizon",
                     "give the horizon or m (horizon = m x lattice spacing), not both");
  const double dx = sc.grid.cell_size;
  p.horizon = h_given ? P.at("horizon") : (m_given ? P.at("m") : 3.0) * dx;
  check_horizon(sc, p.horizon, h_given ? "horizon" : "m");
  p.partial_volumes = P.choices.at("volume_correction") == "partial";
  if (P.given("thickness")) {
    if (sc.simulation.dimension == Dimension::ThreeD)
      pd_section_error(sc, "thickness", "a thickness belongs to 2D runs (dimension: plane_stress or plane_strain)");
    p.thickness = P.at("thickness");
  }
  p.lattice_calibration = P.choices.at("calibration") == "lattice";
  p.lps = P.choices.at("formulation") == "lps";
  p.surface_correction = P.choices.at("surface_correction") == "energy";
  if (P.given("yield_stress")) p.yield_stress = P.at("yield_stress");
  if (P.given("flow_stress")) {
    if (p.yield_stress)
      pd_section_error(sc, "flow_stress", "give yield_stress (the bonds' first yield) or flow_stress, not both");
    if (p.lps)
      pd_section_error(sc, "flow_stress",
                       "flow_stress calibrates micro-plastic bonds; with formulation lps, yield_stress is already "
                       "the von Mises yield stress");
    // The bonds' first yield that puts the uniaxial plateau at the given stress (bond_constants.hpp).
    const int dim = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
    p.yield_stress = P.at("flow_stress") / pd::micro_plastic_flow_factor(dim);
  }
  if (P.given("critical_stretch") && P.given("fracture_energy"))
    pd_section_error(sc, "fracture_energy", "give critical_stretch or fracture_energy, not both");
  if (P.given("critical_stretch")) p.critical_stretch = P.at("critical_stretch");
  if (P.given("fracture_energy")) p.fracture_energy = P.at("fracture_energy");
  p.bond_law_fracture_work = P.choices.at("fracture_work") == "bond_law";
  if (p.bond_law_fracture_work && !(p.fracture_energy && p.yield_stress))
    pd_section_error(sc, "fracture_work",
                     "bond_law sets the critical stretch of micro-plastic bonds from the fracture energy: give "
                     "fracture_energy and yield_stress (or flow_stress)");
  p.stretch_alpha = P.at("stretch_alpha");
  p.stretch_scatter = P.at("stretch_scatter");
  if (P.given("scatter_seed")) {
    const double seed = P.at("scatter_seed");
    if (seed != std::floor(seed)) pd_section_error(sc, "scatter_seed", "expected a whole number");
    if (p.stretch_scatter == 0.0)
      pd_section_error(sc, "scatter_seed", "a seed draws the critical-stretch scatter, but stretch_scatter is 0");
    p.scatter_seed = static_cast<std::uint64_t>(seed);
  }
  p.dt_safety = P.at("dt_safety");
  p.fragment_interval = P.at("fragment_interval");
  if (P.given("fragment_damage_threshold")) p.fragment_damage_threshold = P.at("fragment_damage_threshold");
  p.contact = P.choices.at("contact") == "on";
  p.contact_all_pairs = P.choices.at("contact_pairs") == "all";
  p.lammps_break = P.choices.at("break_rule") == "lammps";
  p.contact_skin = P.at("contact_skin");
  if (const double every = P.at("gas_refamily_steps"); every > 0.0) {
    if (every != std::floor(every)) pd_section_error(sc, "gas_refamily_steps", "expected a whole number of steps");
    p.gas_refamily_steps = static_cast<int>(every);
  }
  if (p.lps) check_lps(sc, p);
  return p;
}

}  // namespace ballista
