// B4 cantilever first mode, slow part: the period and the energy for H / cell_size = 2, 4, 8 (and
// 16 for the smooth shape functions) with linear, GIMP, CPDI and bspline3, against Euler-Bernoulli
// and Timoshenko theory (the shear-locking indication: a period that shortens as H spans fewer
// cells). See test_b4_cantilever.cpp and docs/validation.md ("B4").
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "verification/cantilever_support.hpp"

namespace slow_b4_cantilever {

using namespace ballista;
using namespace ballista::verification;

namespace {
// Extra --set overrides of every run: add e.g. "mpm.anti_locking=fbar" here to repeat the study
// with another solver option.
const std::vector<std::string> kOverrides = {};
}  // namespace

// One test per shape function (ctest runs them side by side): H / h = 2, 4, 8, the period against
// Timoshenko and the energy drift; every row is printed (ctest -V) and recorded.
void period_table(const std::string& sf, const std::vector<std::string>& overrides = kOverrides,
                  const std::string& tag = "") {
  const Scenario sc = load_example("cantilever_beam.yaml");
  const BeamData b = beam_data(sc);
  const double T_eb = euler_bernoulli_period(b), T_ti = timoshenko_period(b);
  std::printf("B4 cantilever L = %g m, H = %g m, E' = %g Pa: T(Euler-Bernoulli) = %.5f s, T(Timoshenko) = %.5f s\n",
              b.L, b.H, b.E_plane(), T_eb, T_ti);
  std::printf("  %9s %6s %10s %8s %10s %10s %10s %12s %12s\n", "shape", "H/h", "particles", "steps", "T [s]",
              "T/T_timo", "amp [m]", "dE max", "dE end");
  std::vector<CantileverResult> res;
  for (int cells : {2, 4, 8}) {
    const CantileverResult r = run_cantilever(b.H / cells, sf, overrides);
    res.push_back(r);
    std::printf("  %9s %6d %10ld %8ld %10.5f %10.5f %10.4g %12.3e %12.3e\n", sf.c_str(), cells, r.particles, r.steps,
                r.period, r.period / T_ti, r.amplitude, r.energy_drift, r.energy_end);
    if (!r.failure.empty()) std::printf("            stopped at t = %.4g s: %s\n", r.failed_at, r.failure.substr(0, 120).c_str());
    report(sf + tag + "_T_over_Ttimo_H" + std::to_string(cells), r.period / T_ti);
    report(sf + tag + "_energy_drift_H" + std::to_string(cells), r.energy_drift);
  }
  const double finest = res.back().period / T_ti;
  if (tag == "_fbar") {
    // Measured (GIMP + F-bar): 1.0853, 1.0150, 1.0011 of Timoshenko at H/h = 2, 4, 8 (without:
    // 0.9915, 0.9944, 0.9963): F-bar removes the stiff (locking) side and converges from above, to
    // 0.1 % at H/h = 8; energy drift 2.2e-3 there. Bands: within 0.5 %, drift < 1 %.
    EXPECT_NEAR(finest, 1.0, 0.005);
    EXPECT_LT(res.back().energy_drift, 0.01);
    return;
  }
  if (sf == "gimp" || sf == "cpdi") {
    // Measured at H/h = 8: 0.9963 (GIMP), 0.9961 (CPDI), approached from below (locking side); the
    // energy drift 2.1e-3 / 3.6e-3. Bands: within 1 % below Timoshenko, closer than at H/h = 2,
    // drift < 1 %.
    EXPECT_GT(finest, 0.99) << sf;
    EXPECT_LT(finest, 1.0) << sf;
    EXPECT_GT(res.back().period, res.front().period) << sf;
    EXPECT_LT(res.back().energy_drift, 0.01) << sf;
  } else if (sf == "bspline3") {
    // Measured 1.0559, 1.0091, 0.9999 with the boundary-modified basis at the clamp (Steffen et
    // al. 2008; before it, with the face's ghost nodes zeroed, 1.1115, 1.0359, 1.0133: the root
    // rotated). Converging from above to within 0.01 % at H/h = 8; band 0.5 %, drift < 1 %
    // (measured 4.3e-3).
    EXPECT_NEAR(finest, 1.0, 0.005);
    EXPECT_LT(res.back().period, res.front().period);
    EXPECT_LT(res.back().energy_drift, 0.01);
  } else {
    // Linear with USL: only H/h = 2 completes (0.9785; 4 and 8 stop with J <= 0 at the tip corner,
    // as in the thesis).
    EXPECT_NEAR(res.front().period / T_ti, 0.98, 0.01);
  }
}

TEST(B4CantileverSlow, Linear) { period_table("linear"); }
TEST(B4CantileverSlow, Gimp) { period_table("gimp"); }
TEST(B4CantileverSlow, Cpdi) { period_table("cpdi"); }
TEST(B4CantileverSlow, Bspline3) { period_table("bspline3"); }
// The same GIMP study with the F-bar anti-locking option (docs/validation.md, B4).
TEST(B4CantileverSlow, GimpFBar) { period_table("gimp", {"mpm.anti_locking=fbar"}, "_fbar"); }

}  // namespace slow_b4_cantilever
