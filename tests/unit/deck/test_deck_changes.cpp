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

}  // namespace test_deck_changes
