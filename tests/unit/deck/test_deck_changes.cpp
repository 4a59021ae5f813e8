// What a restart may change (deck/deck_changes.hpp): the keys two resolved decks differ in, and
// the rule that only the run's end, outputs, checkpoints, limits and guards may change.
#include <gtest/gtest.h>

#include "deck/deck_changes.hpp"

namespace test_deck_changes {

using namespace ballista;

TEST(DeckChanges, NamesEveryLeafThatDiffersWithItsValues) {
  const std::string a =
      "simulation: {end_time: 1.0e-4, cfl: 0.3}\n"
      "materials:\n  steel: {density: 7850, youngs_modulus: 2.0e11}\n"
      "bodies:\n  - {name: a, velocity: [1, 0]}\n  - {name: b}\n"
      "output: {interval: 1.0e-5}\n";
  const std::string b =
      "simulation: {end_time: 2.0e-4, cfl: 0.3}\n"
      "materials:\n  steel: {density: 7850, youngs_modulus: 1.0e11}\n"
      "bodies:\n  - {name: a, velocity: [1, 2]}\n  - {name: b, radial_velocity: 3}\n"
      "output: {interval: 1.0e-5, checkpoint_interval: 1.0e-5}\n";
  const std::vector<DeckChange> c = deck_changes(a, b);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c[0].key_path, "bodies.0.velocity.1");
  EXPECT_EQ(c[0].before, "0");
  EXPECT_EQ(c[0].after, "2");
  EXPECT_EQ(c[1].key_path, "bodies.1.radial_velocity");
  EXPECT_EQ(c[1].before, "");  // not given before
  EXPECT_EQ(c[2].key_path, "materials.steel.youngs_modulus");
  EXPECT_EQ(c[3].key_path, "output.checkpoint_interval");
  EXPECT_EQ(c[4].key_path, "simulation.end_time");
  EXPECT_TRUE(deck_changes(a, a).empty());
}

TEST(DeckChanges, AListOfAnotherLengthIsOneChange) {
  const std::vector<DeckChange> c = deck_changes("probes: [{name: a}]\n", "probes: [{name: a}, {name: b}]\n");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].key_path, "probes");
}

TEST(DeckChanges, ARestartMayChangeTheEndOutputsLimitsAndGuardsOnly) {
  for (const char* ok : {"simulation.end_time", "simulation.max_steps", "simulation.step_limit",
                         "simulation.energy_drift_limit", "simulation.threads", "output.interval",
                         "output.checkpoint_interval", "output.fields.2", "output"})
    EXPECT_TRUE(restart_may_change(ok)) << ok;
  for (const char* no : {"simulation.cfl", "simulation.max_dt", "simulation.damping", "materials.steel.density",
                         "grid.cell_size", "bodies.0.velocity.1", "mpm.update", "probes", "outputs.interval"})
    EXPECT_FALSE(restart_may_change(no)) << no;
}

// The refused changes are exactly one, at key_path.
void expect_one_change(const std::vector<DeckChange>& r, const std::string& key_path) {
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].key_path, key_path);
}

// A checkpoint written before a key existed: its deck lacks the key, and this build resolves it at
// its default. That is no change (a key's default is the behaviour before it existed); the same key
// set by an override, a new key set inside a new section, and a removed or changed key still are.
TEST(DeckChanges, AKeyAddedSinceTheCheckpointIsNoChangeAtItsDefault) {
  const std::string stored = "mpm: {bulk_viscosity_linear: 0.2}\nsimulation: {end_time: 1.0e-4}\n";
  const std::string plain =
      "mpm: {bulk_viscosity_linear: 0.2, bulk_viscosity_sound_speed: current}\nsimulation: {end_time: 1.0e-4}\n"
      "anti_locking: {patch: 1}\n";
  EXPECT_TRUE(refused_restart_changes(stored, plain, plain).empty());
  // An override of the new key to another value is refused, naming it.
  const std::string set =
      "mpm: {bulk_viscosity_linear: 0.2, bulk_viscosity_sound_speed: reference}\nsimulation: {end_time: 1.0e-4}\n"
      "anti_locking: {patch: 1}\n";
  std::vector<DeckChange> r = refused_restart_changes(stored, plain, set);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].key_path, "mpm.bulk_viscosity_sound_speed");
  EXPECT_EQ(r[0].before, "");
  EXPECT_EQ(r[0].after, "reference");
  // A whole new section is one change at its path; an override inside it refuses it.
  const std::string inside =
      "mpm: {bulk_viscosity_linear: 0.2, bulk_viscosity_sound_speed: current}\nsimulation: {end_time: 1.0e-4}\n"
      "anti_locking: {patch: 2}\n";
  expect_one_change(refused_restart_changes(stored, plain, inside), "anti_locking");
  // An existing key changed, or one the checkpoint has and this build drops, stays refused; the
  // run's end may still change.
  const std::string changed =
      "mpm: {bulk_viscosity_linear: 0.3, bulk_viscosity_sound_speed: current}\nsimulation: {end_time: 2.0e-4}\n"
      "anti_locking: {patch: 1}\n";
  expect_one_change(refused_restart_changes(stored, changed, changed), "mpm.bulk_viscosity_linear");
  r = refused_restart_changes(plain, stored, stored);
  ASSERT_EQ(r.size(), 2u);  // bulk_viscosity_sound_speed and anti_locking removed
}

// A key the checkpoint's deck holds as null (an optional value not given, `key: ~`) existed when
// it was written: a value for it now is a change, default or not. And a key added with a default
// that changes what some runs do is refused although absent.
TEST(DeckChanges, ANullKeyOrAKeyWhoseDefaultChangedPhysicsIsStillAChange) {
  const std::string stored = "materials:\n  cu: {eos: {max_particle_velocity: ~}}\n";
  const std::string now = "materials:\n  cu: {eos: {max_particle_velocity: 5000}}\n";
  std::vector<DeckChange> r = refused_restart_changes(stored, now, now);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].key_path, "materials.cu.eos.max_particle_velocity");
  EXPECT_FALSE(r[0].before_absent);
  const std::string old_mpm = "mpm: {bulk_viscosity_linear: 0.2}\n";
  const std::string new_mpm = "mpm: {bulk_viscosity_linear: 0.2, distortion_limit: 1000}\n";
  r = refused_restart_changes(old_mpm, new_mpm, new_mpm);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].key_path, "mpm.distortion_limit");
  EXPECT_TRUE(r[0].before_absent);
}

}  // namespace test_deck_changes
