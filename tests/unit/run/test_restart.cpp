// Checkpoint and restart at the run level (issue 16, docs/restart.md): a run restarted from a
// checkpoint continues exactly as the uninterrupted one (history.csv byte for byte, the probes,
// the particle files, the stage log); a failing run leaves a checkpoint of its last good step,
// from which the failure is reproduced at the same step; what cannot be continued is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "io/checkpoint_file.hpp"
#include "run/restart_checks.hpp"
#include "run/simulation.hpp"
#include "support/test_files.hpp"

namespace test_restart {

namespace fs = std::filesystem;
using namespace ballista;
using ballista::test::slurp;
using ballista::test::TempDir;

namespace {

RunOptions options(const fs::path& dir, const std::string& restart = "") {
  RunOptions o;
  o.out_dir = dir.string();
  o.progress = false;
  o.threads = 1;
  o.restart_from = restart;
  return o;
}

// A J2 block thrown against a wall (plastic flow, contact with the wall) with a damped preparation
// stage first, particle outputs and checkpoints every 2e-5 s.
const std::string kBlock =
    "simulation: {dimension: plane_strain, end_time: 1.0e-4}\n"
    "grid: {lower: [0, 0], upper: [0.03125, 0.03125], cell_size: 0.00390625, boundary: {x_min: wall}}\n"
    "materials:\n"
    "  metal: {model: j2_plasticity, density: 2700, youngs_modulus: 7.0e10, poisson_ratio: 0.3, "
    "yield_stress: 1.0e8, hardening_modulus: 1.0e8}\n"
    "bodies:\n"
    "  - {name: block, material: metal, velocity: [-150, 0], shape: {type: box, lower: [0.00390625, 0.01171875], "
    "upper: [0.015625, 0.0234375]}}\n"
    "stages:\n"
    "  - {name: settle, duration: 1.0e-5, damping: 100}\n"
    "probes:\n"
    "  - {name: eqps_max, type: field_max, field: eqps}\n"
    "output: {interval: 2.0e-5, history_every: 3, checkpoint_interval: 2.0e-5}\n";

// Two putty slabs colliding at +-50 m/s: a particle inverts (tests/verification/test_replay.cpp).
const std::string kPutty =
    "simulation: {dimension: plane_strain, end_time: 1.0e-3, cfl: 1.0}\n"
    "grid: {lower: [0, 0], upper: [0.0625, 0.03125], cell_size: 0.00390625}\n"
    "materials:\n"
    "  putty: {model: linear_elastic, density: 1000, youngs_modulus: 100, poisson_ratio: 0.25}\n"
    "bodies:\n"
    "  - {name: left, material: putty, velocity: [50, 0], shape: {type: box, lower: [0.00390625, 0.01171875], upper: "
    "[0.009765625, 0.01953125]}}\n"
    "  - {name: slab, material: putty, velocity: [-50, 0], shape: {type: box, lower: [0.041015625, 0.01171875], "
    "upper: [0.046875, 0.01953125]}}\n"
    "output: {interval: 5.0e-5, checkpoint_interval: 1.0e-4}\n";

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Restart, ContinuesBitwiseFromEveryCheckpoint) {
  TempDir ref("restart_ref");
  const Scenario sc = parse_deck(kBlock, "block.yaml", {"output.checkpoint_keep=10"});
  const RunResult full = run_simulation(sc, options(ref.path));
  ASSERT_TRUE(full.ok) << full.error;
  const std::vector<std::string> cks = list_checkpoints(ref.path.string());
  // The initial state, then every 2e-5 s of simulated time but the end: one in the stage.
  ASSERT_GE(cks.size(), 5u);
  const std::string history = slurp(ref.path / "history.csv");
  const std::vector<fs::path> files = ballista::test::h5_files(ref.path);
  for (std::size_t k = 0; k < cks.size(); ++k) {
    TempDir copy("restart_copy");
    fs::copy(ref.path, copy.path, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    const std::string from = (copy.path / "checkpoints" / fs::path(cks[k]).filename()).string();
    const RunResult r = run_simulation(sc, options(copy.path, from));
    ASSERT_TRUE(r.ok) << r.error;
    EXPECT_EQ(r.steps, full.steps) << from;
    EXPECT_EQ(r.probes, full.probes) << from;
    EXPECT_TRUE(slurp(copy.path / "history.csv") == history) << "restart from " << from;
    const std::vector<fs::path> again = ballista::test::h5_files(copy.path);
    ASSERT_EQ(again.size(), files.size()) << from;
    // The particle files carry no time stamps (io/hdf5_handle.hpp): equal states give equal bytes.
    for (std::size_t f = 0; f < files.size(); ++f)
      EXPECT_TRUE(slurp(again[f]) == slurp(files[f])) << files[f].filename() << " after a restart from " << from;
    EXPECT_TRUE(slurp(copy.path / "particles.xdmf") == slurp(ref.path / "particles.xdmf")) << from;
  }
}

TEST(Restart, AThreadCountChangeKeepsTheResultBitwise) {
  // MPM's scatter and reductions do not depend on the thread count (docs/performance.md), so a
  // checkpoint of a 2-thread run continues on 1 thread to the same bits.
  TempDir ref("restart_t2");
  const Scenario sc = parse_deck(kBlock, "block.yaml");
  RunOptions two = options(ref.path);
  two.threads = 2;
  ASSERT_TRUE(run_simulation(sc, two).ok);
  TempDir copy("restart_t1");
  fs::copy(ref.path, copy.path, fs::copy_options::recursive);
  const auto [from, deck] = newest_checkpoint(copy.path.string());
  EXPECT_EQ(deck, sc.resolved_yaml);
  ASSERT_TRUE(run_simulation(parse_deck(deck, "resolved.yaml"), options(copy.path, from)).ok);
  EXPECT_EQ(slurp(copy.path / "history.csv"), slurp(ref.path / "history.csv"));
}

TEST(Restart, AFailingRunCheckpointsItsLastGoodStepAndFailsAgainFromIt) {
  TempDir dir("restart_fail");
  const Scenario sc = parse_deck(kPutty, "putty.yaml");
  const RunResult r1 = run_simulation(sc, options(dir.path));
  ASSERT_FALSE(r1.ok);
  ASSERT_GE(r1.failed_particle, 0) << r1.error;
  // The particle inverts inside a step; the checkpoint is the state before that step, rebuilt by
  // replaying from the newest periodic checkpoint.
  ASSERT_EQ(r1.checkpoint, checkpoint_path(dir.path.string(), r1.failed_step - 1)) << r1.error;
  ASSERT_TRUE(fs::exists(r1.checkpoint));
  const RunResult r2 = run_simulation(sc, options(dir.path, r1.checkpoint));
  ASSERT_FALSE(r2.ok);
  EXPECT_EQ(r2.failed_particle, r1.failed_particle);
  EXPECT_EQ(r2.failed_step, r1.failed_step);
  EXPECT_EQ(r2.error, r1.error);
  EXPECT_EQ(r2.steps, r1.steps);
  // The restarted run fails before its first checkpoint: it replays from the one it started from.
  EXPECT_EQ(r2.checkpoint, r1.checkpoint);
}

TEST(Restart, ADriftGuardFailureCheckpointsTheStartOfItsStep) {
  // The energy-drift guard stops the run on a history row, after the step. The checkpoint is the
  // state at the start of that step (replayed), with the outputs as they were then; restarting
  // from it with the guard on fails again at the same step, and with the guard off the run
  // continues to the history of a run that never stopped.
  TempDir dir("restart_drift");
  const Scenario guarded = parse_deck(kBlock, "block.yaml", {"simulation.energy_drift_limit=1e-12"});
  const RunResult r1 = run_simulation(guarded, options(dir.path));
  ASSERT_FALSE(r1.ok);
  ASSERT_NE(r1.error.find("energy drift"), std::string::npos) << r1.error;
  EXPECT_EQ(r1.checkpoint, checkpoint_path(dir.path.string(), r1.failed_step - 1));
  const RunResult again = run_simulation(guarded, options(dir.path, r1.checkpoint));
  EXPECT_FALSE(again.ok);
  EXPECT_EQ(again.failed_step, r1.failed_step);
  EXPECT_EQ(again.error, r1.error);
  const RunResult r2 = run_simulation(parse_deck(kBlock, "block.yaml"), options(dir.path, again.checkpoint));
  ASSERT_TRUE(r2.ok) << r2.error;
  TempDir ref("restart_drift_ref");
  const RunResult full = run_simulation(parse_deck(kBlock, "block.yaml"), options(ref.path));
  EXPECT_EQ(r2.probes, full.probes);
  EXPECT_EQ(r2.steps, full.steps);
  EXPECT_TRUE(slurp(dir.path / "history.csv") == slurp(ref.path / "history.csv"));
}

TEST(Restart, WhatCannotBeContinuedIsRefused) {
  TempDir dir("restart_refused");
  const Scenario sc = parse_deck(kBlock, "block.yaml");
  ASSERT_TRUE(run_simulation(sc, options(dir.path)).ok);
  const auto [from, deck] = newest_checkpoint(dir.path.string());
  // Tracks cannot start in the middle of a run: their F-tables would miss the steps before.
  const std::string tracks = error_of([&] {
    run_simulation(parse_deck(deck, "d.yaml", {"output.track.ids=[3]"}), options(dir.path, from));
  });
  EXPECT_NE(tracks.find("written without output.track.ids"), std::string::npos) << tracks;
  // Other physics (a failure criterion, a modulus, the grid): a restart continues the checkpoint's
  // run, so the deck may change only its end, outputs, checkpoints, limits and guards; the
  // refusal names the key and both values.
  const std::string other = error_of([&] {
    run_simulation(parse_deck(deck, "d.yaml", {"materials.metal.failure.criterion=max_stress",
                                               "materials.metal.failure.max_stress=1e9"}),
                   options(dir.path, from));
  });
  EXPECT_NE(other.find("the deck changes materials.metal.failure.criterion (none -> max_stress)"), std::string::npos)
      << other;
  const std::string modulus = error_of([&] {
    run_simulation(parse_deck(deck, "d.yaml", {"materials.metal.youngs_modulus=1e11"}), options(dir.path, from));
  });
  EXPECT_NE(modulus.find("materials.metal.youngs_modulus (7e+10 -> 1e+11)"), std::string::npos) << modulus;
  const std::string grid = error_of([&] {
    run_simulation(parse_deck(deck, "d.yaml", {"grid.cell_size=0.0078125"}), options(dir.path, from));
  });
  EXPECT_NE(grid.find("grid.cell_size"), std::string::npos) << grid;
  // Repeating the original values is no change.
  EXPECT_TRUE(run_simulation(parse_deck(deck, "d.yaml", {"materials.metal.youngs_modulus=7.0e10"}),
                             options(dir.path, from)).ok);
}

// A checkpoint written by a build before a key existed: its stored deck lacks the key. This build
// continues it at the key's default, and refuses the key set to anything else, naming it.
TEST(Restart, AKeyAddedSinceTheCheckpointContinuesAtItsDefaultOnly) {
  std::string older = parse_deck(kBlock, "block.yaml").resolved_yaml;
  const std::string line = "bulk_viscosity_sound_speed: current";
  const std::size_t at = older.find(line);
  ASSERT_NE(at, std::string::npos) << older;
  const std::size_t start = older.rfind('\n', at) + 1;
  older.erase(start, older.find('\n', at) + 1 - start);
  StateArchive a;
  a.put_text("run.deck", older);
  EXPECT_NO_THROW(check_restart_changes(a, parse_deck(older, "d.yaml"), "c.h5"));
  const std::string set = error_of([&] {
    check_restart_changes(a, parse_deck(older, "d.yaml", {"mpm.bulk_viscosity_sound_speed=reference"}), "c.h5");
  });
  EXPECT_NE(set.find("mpm.bulk_viscosity_sound_speed (not given -> reference)"), std::string::npos) << set;
  EXPECT_NO_THROW(
      check_restart_changes(a, parse_deck(older, "d.yaml", {"mpm.bulk_viscosity_sound_speed=current"}), "c.h5"));
}

TEST(Restart, AnEndBeforeTheCheckpointIsRefusedAndTheContinuedDeckIsRecorded) {
  TempDir dir("restart_end");
  const Scenario sc = parse_deck(kBlock, "block.yaml");
  ASSERT_TRUE(run_simulation(sc, options(dir.path)).ok);
  const auto [from, deck] = newest_checkpoint(dir.path.string());
  // The newest checkpoint is at 1e-4 - 2e-5 of the main stage: an end of 1e-5 lies before it
  // (it reported "completed" without a step).
  const std::string early = error_of([&] {
    run_simulation(parse_deck(deck, "d.yaml", {"simulation.end_time=1.0e-5"}), options(dir.path, from));
  });
  EXPECT_NE(early.find("before the checkpoint's"), std::string::npos) << early;
  ASSERT_TRUE(
      run_simulation(parse_deck(deck, "d.yaml", {"simulation.end_time=1.5e-4"}), options(dir.path, from)).ok);
  // resolved.yaml is the deck the run was continued with.
  EXPECT_NE(slurp(dir.path / "resolved.yaml").find("end_time: 0.00015"), std::string::npos)
      << slurp(dir.path / "resolved.yaml");
}

// Peridynamic products on their own lattice (bodies[].point_spacing): a restart with another
// spacing would seed other gas points under the checkpoint's ids, so it is refused, naming the body.
TEST(Restart, AnotherPointSpacingIsRefused) {
  const std::string deck_pd = R"(
simulation: {solver: peridynamics, dimension: plane_strain, end_time: 2.0e-6}
materials:
  tnt: {preset: tnt}
  steel: {model: linear_elastic, density: 7850, bulk_modulus: 160.0e9, shear_modulus: 79.0e9}
grid: {lower: [-0.01, -0.01], upper: [0.01, 0.01], cell_size: 0.5e-3}
bodies:
  - {name: charge, material: tnt, point_spacing: 1.0e-3, shape: {type: box, lower: [-4.0e-3, -4.0e-3], upper: [2.0e-3, 4.0e-3]}}
  - {name: plate, material: steel, shape: {type: box, lower: [2.0e-3, -4.0e-3], upper: [4.0e-3, 4.0e-3]}}
detonation: {points: [{position: [-4.0e-3, 0], time: 0}]}
output: {interval: 1.0e-6, checkpoint_interval: 1.0e-6}
)";
  TempDir dir("restart_point_spacing");
  ASSERT_TRUE(run_simulation(parse_deck(deck_pd, "pd.yaml"), options(dir.path)).ok);
  const auto [from, deck] = newest_checkpoint(dir.path.string());
  const std::string err = error_of([&] {
    run_simulation(parse_deck(deck, "d.yaml", {"bodies.0.point_spacing=1.5e-3"}), options(dir.path, from));
  });
  EXPECT_NE(err.find("bodies.0.point_spacing (0.001 -> 0.0015)"), std::string::npos) << err;
  // The same spacing continues.
  EXPECT_TRUE(run_simulation(parse_deck(deck, "d.yaml"), options(dir.path, from)).ok);
}

TEST(Restart, WallClockCheckpointsKeepTheNewestTwo) {
  // --checkpoint-every-minutes with a tiny interval: a checkpoint after every step (none at the
  // end), of which the newest output.checkpoint_keep = 2 remain: the last two steps before the end.
  TempDir dir("restart_wall");
  const Scenario sc = parse_deck(kBlock, "block.yaml", {"output.checkpoint_interval=0"});
  RunOptions o = options(dir.path);
  o.checkpoint_minutes = 1e-12;
  const RunResult r = run_simulation(sc, o);
  ASSERT_TRUE(r.ok) << r.error;
  const std::vector<std::string> cks = list_checkpoints(dir.path.string());
  ASSERT_EQ(cks.size(), 2u);
  EXPECT_EQ(cks[0], checkpoint_path(dir.path.string(), r.steps - 2));
  EXPECT_EQ(cks[1], checkpoint_path(dir.path.string(), r.steps - 1));
  // Restarted with the simulated-time interval switched off (it was on): wall-clock checkpoints
  // only, and the run ends.
  TempDir again("restart_wall_again");
  ASSERT_TRUE(run_simulation(parse_deck(kBlock, "block.yaml"), options(again.path)).ok);
  const auto [from, deck] = newest_checkpoint(again.path.string());
  RunOptions o2 = options(again.path, from);
  o2.checkpoint_minutes = 1e-12;
  const RunResult r2 = run_simulation(parse_deck(deck, "d.yaml", {"output.checkpoint_interval=0"}), o2);
  ASSERT_TRUE(r2.ok) << r2.error;
  EXPECT_EQ(r2.steps, r.steps);
}

TEST(Restart, ALaterEndTimeContinuesTheRun) {
  // --set simulation.end_time on a restart: the run goes on to the new end from where it stopped.
  TempDir dir("restart_longer");
  const Scenario sc = parse_deck(kBlock, "block.yaml");
  const RunResult first = run_simulation(sc, options(dir.path));
  ASSERT_TRUE(first.ok) << first.error;
  const auto [from, deck] = newest_checkpoint(dir.path.string());
  const RunResult longer =
      run_simulation(parse_deck(deck, "resolved.yaml", {"simulation.end_time=2.0e-4"}), options(dir.path, from));
  ASSERT_TRUE(longer.ok) << longer.error;
  // The main stage starts after the 1e-5 s stage: it ends 2e-4 s later.
  EXPECT_NEAR(longer.time, 2.1e-4, 1e-12);
  EXPECT_GT(longer.steps, first.steps);
}

TEST(Restart, TrackedParticlesContinueTheirTables) {
  // output.track.ids: the F-tables and in-solver histories of the tracked particles are cut back
  // to the checkpoint and continued, byte for byte those of the uninterrupted run.
  TempDir ref("restart_tracks_ref");
  const Scenario sc = parse_deck(kBlock, "block.yaml", {"output.track.ids=[0,17]"});
  ASSERT_TRUE(run_simulation(sc, options(ref.path)).ok);
  TempDir copy("restart_tracks");
  fs::copy(ref.path, copy.path, fs::copy_options::recursive);
  const std::vector<std::string> cks = list_checkpoints(copy.path.string());
  ASSERT_EQ(cks.size(), 2u);
  fs::remove(cks[1]);  // from the older one: the rows after it are cut and written again
  ASSERT_TRUE(run_simulation(sc, options(copy.path, cks[0])).ok);
  for (const char* f : {"particle_0.csv", "particle_0_history.csv", "particle_17.csv", "particle_17_history.csv"}) {
    const std::string a = slurp(ref.path / "tracks" / f), b = slurp(copy.path / "tracks" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_TRUE(a == b) << f;
  }
  EXPECT_TRUE(slurp(ref.path / "history.csv") == slurp(copy.path / "history.csv"));
  // A particle tracked only from the restart on is refused (its table would miss the start).
  const std::string added = error_of([&] {
    run_simulation(parse_deck(kBlock, "block.yaml", {"output.track.ids=[0,5,17]"}), options(copy.path, cks[0]));
  });
  EXPECT_NE(added.find("adds particle 5"), std::string::npos) << added;
}

}  // namespace test_restart
