// Verification of MPM on a grid with a patch of finer cells (grid.patches, hanging nodes around
// it: mpm/patch_constraints.hpp):
//  - a stress pulse crossing from the patch's fine cells into the coarse ones leaves little of
//    its energy behind (the reflection at the patch's face), beyond what the uniform fine grid
//    leaves;
//  - B1 (axis-aligned MMS) keeps its observed order with a patch inside the cube, and B2
//    (generalized vortex MMS) with patches across the annulus (nested ones with GIMP);
//  - patches dropped mid-run (until) hand their points to the coarse grid: momentum kept, the
//    step the coarse cells', no energy lost beyond what the coarse grid loses;
//  - a cylinder prestressed to its confinement's stress stays at rest with nested patches in it
//    (uGIMP weights on each region's own cells: a uniform stress is in equilibrium).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/state_archive.hpp"
#include "deck/deck_reader.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"
#include "verification/verification_support.hpp"

namespace test_grid_patches {

using namespace ballista;
using namespace ballista::verification;

namespace {

std::string num(double x) {
  return fmt::format("{:.17g}", x);
}

// The bar of test_graded_grid.cpp (uniaxial strain along x, E = rho = 1 so c = 1 m/s, a smooth
// velocity bump v0 cos^2(pi x / 2w) for |x| < w in layers of 1/80 m), here with cells of 1/80 in
// a patch over |x| < 0.5 nested in one of 1/40 over |x| < 0.75, both the bar's whole height, and
// 1/20 outside: each change of cell size is abrupt (2:1), where the graded test's is spread over
// cells growing by 1.2.
std::string bar_deck(bool patched, bool coarse = false, const std::string& until = "") {
  const double w = 0.2, layer = 1.0 / 80.0, v0 = 1.0e-3;
  std::string d =
      "simulation: {solver: mpm, dimension: plane_strain, end_time: 1.25, cfl: 0.3}\n"
      "mpm: {shape_function: gimp, update: usl, flip: 1.0}\n"
      "materials:\n  m: {model: linear_elastic, density: 1, youngs_modulus: 1, poisson_ratio: 0}\n"
      "grid: {lower: [-2.0, 0.0], upper: [2.0, 0.05], cell_size: " +
      std::string(patched || coarse ? "0.05" : "0.0125") +
      ", boundary: {y_min: symmetry, y_max: symmetry}" +
      (patched ? ", patches: [{lower: [-0.75, 0.0], upper: [0.75, 0.05], cell_size: 0.025" + until +
                     "}, {lower: [-0.5, 0.0], upper: [0.5, 0.05], cell_size: 0.0125" + until + "}]"
               : "") +
      "}\nbodies:\n";
  auto body = [&](const std::string& name, double lo, double hi, double v) {
    d += "  - {name: " + name + ", material: m, velocity: [" + num(v) +
         ", 0], shape: {type: box, lower: [" + num(lo) + ", 0.0], upper: [" + num(hi) +
         ", 0.05]}}\n";
  };
  body("left", -2.0, -w, 0.0);
  const int layers = static_cast<int>(std::lround(2 * w / layer));
  for (int k = 0; k < layers; ++k) {
    const double lo = -w + k * layer, mid = lo + 0.5 * layer;
    const double c = std::cos(std::acos(-1.0) * mid / (2 * w));
    body("layer" + std::to_string(k), lo, lo + layer, v0 * c * c);
  }
  body("right", w, 2.0, 0.0);
  return d;
}

/// Kinetic + internal energy of the points that started within |x| < 0.45 (the patch), over the
/// total, at the end; and the total's change over the run relative to it. `coarse`: the uniform
/// grid of the patched deck's coarse cells.
struct Left {
  double behind = 0.0, drift = 0.0;
  Index points = 0;
};

Left energy_left_behind(bool patched, bool coarse = false) {
  const Scenario sc =
      parse_deck(bar_deck(patched, coarse), patched ? "patched_bar.yaml" : "uniform_bar.yaml");
  auto solver = make_solver(sc);
  const double total = solver->energies().total();
  advance(*solver, sc.simulation.end_time);
  const FieldStore& pts = solver->points();
  const auto* x0 = pts.view<Vec3>("x0");
  const auto* v = pts.view<Vec3>("v");
  const auto* m = pts.real("mass");
  const auto* e = pts.real("internal_energy");
  double inside = 0.0, all = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    const double ep = 0.5 * m[p] * dot(v[p], v[p]) + e[p];
    all += ep;
    if (std::abs(x0[p][0]) < 0.45) inside += ep;
  }
  return {inside / total, (all - total) / total, pts.size()};
}

}  // namespace

TEST(GridPatches, APulseLeavingAPatchLeavesLittleBehind) {
  const Left patched = energy_left_behind(true), uniform = energy_left_behind(false);
  const Left coarse = energy_left_behind(false, true);
  std::printf(
      "pulse energy left in the patch: patched %.3e (%ld points), uniform fine %.3e (%ld), uniform "
      "coarse %.3e\n"
      "energy change over the run: patched %.2e, fine %.2e, coarse %.2e\n",
      patched.behind, patched.points, uniform.behind, uniform.points, coarse.behind, patched.drift,
      uniform.drift, coarse.drift);
  report("patch_reflection", patched.behind - uniform.behind);
  // Measured: patched 3.8e-3, fine 8.1e-4, coarse 1.5e-2 (the coarse cells' own dispersive tail).
  // The change of cell size is asked to reflect under 1 % (as a graded grid's); the fine grid's
  // remainder is the dispersive tail, so the patch's reflection is what it leaves beyond that.
  EXPECT_LT(uniform.behind, 0.01);  // not vacuous: the pulses did leave the patch
  EXPECT_LT(patched.behind - uniform.behind, 0.01);
  // The energy lost over the run is the coarse cells' (USL with pure FLIP dissipates a pulse 8
  // coarse cells long: -10 % on the coarse grid, -0.2 % on the fine one, -2.7 % patched, where
  // the pulses run half their way in coarse cells): the hanging nodes add none of their own.
  EXPECT_LT(std::abs(patched.drift), std::abs(coarse.drift));
  EXPECT_GT(std::abs(patched.drift), std::abs(uniform.drift));
}

TEST(GridPatches, B1KeepsItsOrderWithAPatch) {
  // The B1 cube (GIMP, USL, pure FLIP, 3D) at H = 1/4 and 1/8 with a patch of H/2 cells over
  // [0.25, 0.5] x [0.5, 0.75] x [0.25, 0.75]: hanging nodes with two and four masters around it.
  // The uniform test asserts an order of 1.5 at these sizes (its graded-band variant too); the
  // same bound here. Measured: 3.62e-2 and 1.06e-2 (order 1.77; uniform 3.28e-2 and 9.89e-3).
  // The patch does not make the answer better: 10 % and 7 % more error than the uniform grid's
  // (the cause not examined; the patch covers 1/32 of the cube), bounded here by 15 %.
  const std::vector<double> H = {0.25, 0.125};
  std::vector<MmsError> patched, uniform;
  for (double h : H) {
    patched.push_back(run_mms(
        h, {"grid.patches=[{lower: [0.25, 0.5, 0.25], upper: [0.5, 0.75, 0.75], cell_size: " +
            num(h / 2) + "}]"}));
    uniform.push_back(run_mms(h));
    std::printf("B1 H = %g: patched L2 %.4e (%ld particles), uniform L2 %.4e (%ld)\n", h,
                patched.back().l2, patched.back().particles, uniform.back().l2,
                uniform.back().particles);
  }
  const double order = observed_order(patched[0].l2, patched[1].l2);
  report("patch_b1_order", order);
  EXPECT_GE(order, 1.5);
  for (std::size_t k = 0; k < H.size(); ++k) EXPECT_LT(patched[k].l2, 1.15 * uniform[k].l2) << H[k];
}

TEST(GridPatches, B2KeepsItsOrderWithPatches) {
  // The vortex annulus (radius 0.75 to 1.25) at H = 1/16 and 1/32 with a patch of H/2 cells over
  // [-0.5, 0.5] x [0.5, 1.5] and, with GIMP, one of H/4 nested in it over [-0.25, 0.25] x [0.625,
  // 1.375]: the annulus crosses both, its flow running through their side faces. The uniform test
  // asserts 1.7 (measured 1.96 with GIMP, 1.97 linear); the same bound here. Linear shapes run the
  // single patch: points from the coarse cells, H/2 apart, flowing into the nested patch's H/4
  // cells leave some empty and invert (at H = 1/32, step 276), which the solver warns of.
  for (const char* sf : {"gimp", "linear"}) {
    const bool nested = std::string(sf) == "gimp";
    std::vector<MmsError> e;
    for (double h : {0.0625, 0.03125}) {
      std::string patches = "grid.patches=[{lower: [-0.5, 0.5], upper: [0.5, 1.5], cell_size: " + num(h / 2) + "}";
      if (nested) patches += ", {lower: [-0.25, 0.625], upper: [0.25, 1.375], cell_size: " + num(h / 4) + "}";
      e.push_back(run_vortex(h, sf, {patches + "]"}));
      std::printf("B2 %s H = %g: patched L2 %.4e (%ld particles)\n", sf, h, e.back().l2, e.back().particles);
    }
    const double order = observed_order(e[0].l2, e[1].l2);
    report(std::string("patch_b2_order_") + sf, order);
    EXPECT_GE(order, 1.7) << sf;
  }
}

namespace {

/// Kinetic energy (J) after 10 us of an elastic rock cylinder (E = 20 GPa, nu = 0.2) under its
/// confinement (radial 20 MPa, axial 30 MPa), uGIMP, axisymmetric, 1 mm cells, with these
/// overrides.
double cylinder_kinetic(const std::vector<std::string>& sets) {
  const std::string deck = R"(simulation: {dimension: axisymmetric, end_time: 10.0e-6}
mpm: {shape_function: gimp}
grid: {lower: [0, -0.005], upper: [0.016, 0.03], cell_size: 1.0e-3}
materials:
  rock: {model: linear_elastic, density: 2300, youngs_modulus: 20e9, poisson_ratio: 0.2}
bodies:
  - name: target
    material: rock
    shape: {type: cylinder, center: [0, 0.002], axis: y, radius: 0.01, length: 0.02}
loads:
  - {type: confinement, body: target, radial: 20e6, axial: 30e6, prestress: true}
)";
  test::TempDir dir;
  RunOptions o;
  o.out_dir = dir.path.string();
  o.progress = false;
  const RunResult r = run_simulation(parse_deck(deck, "cylinder.yaml", sets), o);
  EXPECT_TRUE(r.ok) << r.error;
  return YAML::LoadFile((dir.path / "summary.json").string())["energy"]["kinetic"].as<double>();
}

}  // namespace

TEST(GridPatches, DroppedPatchesHandTheirPointsToTheCoarseGrid) {
  // The pulse bar with its nested patches ended at t = 0.3 s (until), while the two pulses are in
  // the fine cells (they leave the 1/80 m patch at about 0.5 s): from the next step the points map
  // to the uniform 1/20 m cells. Truths: the total momentum (free ends, symmetry faces along y
  // only) is what it was, to round-off (measured 1.9e-15 relative); the Courant step
  // cfl l / (c + |v|) grows by the cells' ratio, 4 (|v| <= 1e-3 c moves it by 2e-3 at most); and
  // the pulses, now in coarse cells, lose no more energy than on the coarse grid all along
  // (measured: dropped -7.1 %, coarse -10 %, patched throughout -2.7 %): the drop itself adds
  // no loss of its own.
  const Scenario sc = parse_deck(bar_deck(true, false, ", until: 0.3"), "dropped_bar.yaml");
  auto solver = make_solver(sc);
  auto momentum = [&] { return total_momentum(solver->points()); };
  const double e0 = solver->energies().total(), p0 = momentum();
  const double fine_dt = solver->stable_dt();
  advance(*solver, 0.3);
  const double coarse_dt = solver->stable_dt();  // the patches are dropped here
  advance(*solver, sc.simulation.end_time);
  const double drift = (solver->energies().total() - e0) / e0;
  const double p_change = std::abs(momentum() - p0) / p0;
  const Left coarse = energy_left_behind(false, true);
  std::printf(
      "patches dropped at 0.3 s: step %.4e -> %.4e s (ratio %.4f); momentum change %.1e; energy "
      "change %.2e (coarse grid throughout %.2e)\n",
      fine_dt, coarse_dt, coarse_dt / fine_dt, p_change, drift, coarse.drift);
  report("patch_drop_energy_change", drift);
  EXPECT_NEAR(coarse_dt / fine_dt, 4.0, 4.0 * 2.5e-3);
  EXPECT_LT(p_change, 1e-12);
  EXPECT_LT(drift, 0.0);  // USL with pure FLIP only dissipates
  EXPECT_LT(std::abs(drift), std::abs(coarse.drift));
}

TEST(GridPatches, AStateFromBeforeTheirEndRunsOnThePatchesAgain) {
  // After a failure the run loop loads its newest checkpoint into the solver that failed and
  // replays the steps since; that solver may have dropped its patches after the checkpoint. The
  // pulse bar with patches until 0.3 s: saved at 0.2 s, run on past the drop to 0.35 s, loaded
  // back and run to 0.45 s, it must be bitwise the run that went from 0.2 to 0.45 s straight.
  const Scenario sc = parse_deck(bar_deck(true, false, ", until: 0.3"), "dropped_bar.yaml");
  auto straight = make_solver(sc), replayed = make_solver(sc);
  advance(*straight, 0.2);
  advance(*straight, 0.45);
  advance(*replayed, 0.2);
  StateArchive saved;
  replayed->save_state(saved);
  advance(*replayed, 0.35);
  replayed->load_state(saved);
  advance(*replayed, 0.45);
  ASSERT_EQ(straight->steps(), replayed->steps());
  const FieldStore &a = straight->points(), &b = replayed->points();
  ASSERT_EQ(a.size(), b.size());
  const auto *xa = a.view<Vec3>("x"), *xb = b.view<Vec3>("x");
  const auto *va = a.view<Vec3>("v"), *vb = b.view<Vec3>("v");
  Index differ = 0;
  for (Index p = 0; p < a.size(); ++p)
    for (int d = 0; d < 3; ++d) differ += xa[p][d] != xb[p][d] || va[p][d] != vb[p][d];
  EXPECT_EQ(differ, 0) << "components differing between the straight and the replayed run";
}

TEST(GridPatches, PatchesEndTogether) {
  // A nested patch kept after its parent would split the coarse cells in four, which uGIMP refuses:
  // a deck whose patches end at different times is an error at the one that differs.
  std::string d = bar_deck(true);
  const std::string inner = "cell_size: 0.0125}";
  d.replace(d.find(inner), inner.size(), "cell_size: 0.0125, until: 0.5}");
  try {
    parse_deck(d, "bar.yaml");
    ADD_FAILURE() << "no error for patches ending at different times";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "grid.patches.1.until");
    EXPECT_NE(std::string(e.what()).find("the grid drops its patches together"), std::string::npos) << e.what();
    EXPECT_GT(e.line(), 0);
  }
}

TEST(GridPatches, APrestressedCylinderStaysAtRestWithNestedPatches) {
  // A patch of 0.5 mm cells over r = 2-8 mm, y = 6-18 mm, and one of 0.25 mm nested in it over
  // r = 3-7 mm, y = 8-16 mm (the cylinder spans r < 10 mm, y = 2-22 mm): every face of a patch
  // inside the body. Held by its load from t = 0 in the load's stress, the cylinder should not
  // move (the uniform stress is the exact equilibrium of these tractions; points/prestress.hpp).
  // The same load applied suddenly to the unstressed cylinder rings with a kinetic energy of the
  // order of its elastic energy. Measured after 10 us: with the patches 3.3e-8 J, sudden 5.5e-2 J
  // (ratio 6.0e-7; after 20 us 8.4e-7, and uniform 1 mm cells 1.0e-9 J): the points moved with the
  // prestress's F keep their reference domains, which then overlap by the strain (1e-3) and no
  // longer tile the body exactly where the cell size changes. Bound 1e-5 of the sudden energy, 17
  // times the measured ratio: a force error of a fraction d of the stress's over the body rings
  // with about d^2 of the sudden energy, so the bound holds d below about 0.3 %.
  const std::string patches =
      "grid.patches=[{lower: [0.002, 0.006], upper: [0.008, 0.018], cell_size: 0.5e-3}, "
      "{lower: [0.003, 0.008], upper: [0.007, 0.016], cell_size: 0.25e-3}]";
  const double sudden = cylinder_kinetic({patches, "loads.0.prestress=false"});
  const double patched = cylinder_kinetic({patches});
  std::printf(
      "prestressed cylinder after 10 us: with nested patches %.3e J, the load applied suddenly "
      "%.3e J\n",
      patched, sudden);
  report("patch_prestress_kinetic_ratio", patched / sudden);
  EXPECT_GT(sudden, 1e-3);
  EXPECT_LT(patched, 1e-5 * sudden);
}

}  // namespace test_grid_patches
