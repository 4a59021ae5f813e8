// B5: energy and momentum accounting in an elastic impact (CATALOGUE B5): two neo-Hookean disks
// collide head-on and rebound, plane strain (Sulsky, Chen & Schreyer, CMAME 118 (1994) 179, §5;
// examples/elastic_disks.yaml: pure FLIP, MUSL, GIMP, CFL 0.1). No boundary condition touches the
// disks, so total energy (kinetic + stored strain energy) and linear momentum are invariants of
// the continuous problem; mass is carried by the particles and never changes.
// Read from history.csv of a real `run_simulation` (what a user sees).
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "verification/verification_support.hpp"

namespace test_b5_elastic_disks {

using namespace ballista;
using namespace ballista::verification;

TEST(B5ElasticDisks, EnergyMomentumAndMassAreConserved) {
  // The deck at full size (cell_size 0.025, ~1.6k particles, ~1600 steps; ~2 s on 2 cores).
  const Scenario sc = load_example("elastic_disks.yaml");
  TempDir dir("disks");
  const RunResult r = run_into(sc, dir.str());
  ASSERT_TRUE(r.ok) << r.error;
  const History h = read_history((dir.path() / "history.csv").string());
  ASSERT_GT(h.rows, 100u);

  const auto& E = h["total_energy"];
  const auto& KE = h["kinetic_energy"];
  const auto& SE = h["internal_energy"];
  const auto& m = h["mass"];
  const double E0 = E.front();
  double drift = 0.0, ke_min = KE.front(), se_max = 0.0, p_max = 0.0, m_dev = 0.0;
  for (size_t i = 0; i < h.rows; ++i) {
    drift = std::max(drift, std::abs(E[i] - E0) / E0);
    ke_min = std::min(ke_min, KE[i]);
    se_max = std::max(se_max, SE[i]);
    p_max = std::max(p_max, std::hypot(h["momentum_x"][i], h["momentum_y"][i], h["momentum_z"][i]));
    m_dev = std::max(m_dev, std::abs(m[i] - m.front()));
  }
  // Momentum scale: the sum of the two disks' |momentum| (each m |v0|, 17.8 kg m/s per metre).
  double mass_total = m.front();
  const double p_scale = mass_total * std::hypot(0.1, 0.1);
  std::printf("B5 elastic disks (%zu history rows, %ld steps):\n", h.rows, r.steps);
  report("initial_energy_J", E0);
  report("max_energy_drift_rel", drift);
  report("min_kinetic_over_E0", ke_min / E0);
  report("max_strain_energy_over_E0", se_max / E0);
  report("max_momentum_over_scale", p_max / p_scale);
  report("max_mass_change_rel", m_dev / m.front());

  // The collision really happened: nearly all the kinetic energy turned into strain energy at the
  // turning point (measured KE_min = 3.4 % and SE_max = 96 % of E0), so the drift check below
  // covers the whole exchange, not a free flight.
  EXPECT_LT(ke_min, 0.2 * E0);
  EXPECT_GT(se_max, 0.8 * E0);
  // Energy: pure FLIP + MUSL has no built-in dissipation (PIC's grid averaging is off), so the
  // drift is the explicit time-integration error, which falls with dt. Measured max
  // drift 0.40 % at CFL 0.1. The 1 % limit fails for the known-dissipative or less accurate
  // variants (measured with the same deck: PIC 63 %, USL 2.7 %, MUSL at CFL 0.3 1.2 %), so it
  // does discriminate.
  EXPECT_LT(drift, 0.01);
  // Momentum: the disks start with opposite velocities of mirror-symmetric lattices (total 0) and
  // grid forces sum to zero (partition of unity, no BCs), so momentum stays 0 to round-off.
  // Measured 1e-15 relative; 1e-12 relative allows ~1600 steps of summation round-off and is
  // still 10 orders below any real leak (one stray node force).
  EXPECT_LT(p_max, 1e-12 * p_scale);
  // Mass: particle masses never change; the total is summed in particle order, which the cell
  // sort permutes, so it may change by summation round-off, bounded by n eps (1.6k particles:
  // 4e-13 relative). Measured exactly 0.
  EXPECT_LE(m_dev, 4e-13 * m.front());
}

}  // namespace test_b5_elastic_disks
