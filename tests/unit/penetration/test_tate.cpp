// Alekseevskii-Tate (thesis seed 000 eq. 3.9): the steady root against the textbook quadratic
// formula, and the RK4 time integration against the Walters-Segletes exact solution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/error.hpp"
#include "penetration/hydrodynamic.hpp"
#include "penetration/tate.hpp"
#include "penetration/walters_segletes.hpp"

namespace test_tate {

namespace bp = ballista::penetration;

namespace {
// Tungsten-alloy rod into armour steel, a classical Tate set: R > Y, so the rod stops
// penetrating (U = 0) at V = sqrt(2 (R - Y)/rho_p) = 630.7 m/s.
bp::TateInput tungsten_into_steel() {
  return {0.1, 17600, 7850, 5.0e9, 1.5e9, 1500};
}
}  // namespace

TEST(Tate, SteadyVelocityMatchesQuadraticFormula) {
  // eq. 3.9: (rho_p - rho_t) U^2 - 2 rho_p V U + rho_p V^2 - 2 (R - Y) = 0; the physical root is
  // U = [rho_p V - sqrt(rho_p^2 V^2 - (rho_p - rho_t)(rho_p V^2 - 2(R - Y)))] / (rho_p - rho_t)
  // (textbook form; for rho_p = rho_t the equation is linear: U = (rho_p V^2 - 2(R-Y)) / (2 rho_p V)).
  for (double rho_p : {17600.0, 7850.0, 2700.0}) {
    for (double V : {1000.0, 2000.0, 4000.0}) {
      const bp::TateInput in{0.1, rho_p, 7850, 5.0e9, 1.5e9, V};
      const double s = in.R - in.Y;
      if (rho_p * V * V <= 2 * s) {  // the quadratic's roots are negative or complex: no penetration
        EXPECT_EQ(bp::tate_penetration_velocity(in, V).regime, bp::InterfaceRegime::kNoPenetration);
        continue;
      }
      double U_ref;
      if (rho_p == in.rho_t)
        U_ref = (rho_p * V * V - 2 * s) / (2 * rho_p * V);
      else
        U_ref = (rho_p * V - std::sqrt(rho_p * rho_p * V * V - (rho_p - in.rho_t) * (rho_p * V * V - 2 * s))) /
                (rho_p - in.rho_t);
      const auto r = bp::tate_penetration_velocity(in, V);
      // The textbook form cancels (relative error ~ 1e-16 V / U); 1e-10 relative covers it.
      EXPECT_NEAR(r.U, U_ref, 1e-10 * V) << rho_p << " " << V;
      const double res = 0.5 * rho_p * (V - r.U) * (V - r.U) + in.Y - 0.5 * in.rho_t * r.U * r.U - in.R;
      EXPECT_NEAR(res, 0, 1e-13 * rho_p * V * V);
    }
  }
}

TEST(Tate, StrengthlessRodPenetratesBirkhoffDepth) {
  // R = Y = 0: U is the hydrodynamic velocity and the rod is consumed at constant V: P = eq. 3.2.
  const bp::TateInput in{0.1, 17600, 7850, 0, 0, 2000};
  const auto run = bp::integrate_tate(in);
  EXPECT_EQ(run.stop_reason, "L = 0");
  EXPECT_NEAR(run.final.P, bp::birkhoff_depth(0.1, 17600, 7850), 1e-12);
}

TEST(Tate, Rk4AgreesWithWaltersSegletesAtFourthOrder) {
  const bp::TateInput in = tungsten_into_steel();
  const bp::TateState end = bp::walters_segletes_final(in);
  // Compare at a fixed time, half the exact duration of the eroding phase.
  const double T = 0.5 * end.t;
  const bp::TateState ex = bp::walters_segletes_at_time(in, T);
  double err[3];
  const int spt[3] = {10, 20, 40};  // steps per L0/V0 transit (dt = 6.7, 3.3, 1.7 us; T = 50 us)
  for (int k = 0; k < 3; ++k) {
    bp::TateOptions opt;
    opt.steps_per_transit = spt[k];
    opt.t_end = T;
    opt.record_history = false;
    const auto run = bp::integrate_tate(in, opt);
    EXPECT_EQ(run.stop_reason, "t_end");
    err[k] = std::max({std::abs(run.final.P - ex.P) / in.L0, std::abs(run.final.L - ex.L) / in.L0,
                       std::abs(run.final.V - ex.V) / in.V0});
  }
  const double order1 = std::log2(err[0] / err[1]), order2 = std::log2(err[1] / err[2]);
  std::printf("Tate RK4 vs Walters-Segletes at t = %.4g s: errors %.3e %.3e %.3e, observed orders %.2f %.2f\n", T,
              err[0], err[1], err[2], order1, order2);
  // RK4 is fourth order; +-0.3 allows the pre-asymptotic drift of two halvings.
  EXPECT_NEAR(order2, 4.0, 0.3);
  EXPECT_LT(err[2], 1e-7);
}

TEST(Tate, FinalDepthMatchesWaltersSegletes) {
  const bp::TateInput in = tungsten_into_steel();
  const bp::TateState ex = bp::walters_segletes_final(in);
  const auto run = bp::integrate_tate(in);  // default: 200 steps per L0/V0
  EXPECT_EQ(run.stop_reason, "U = 0");
  std::printf(
      "Tate final (%ld steps): P = %.9f m, rel. error %.2e; L = %.3e m, error %.2e m; t = %.6e s, rel. "
      "error %.2e\n",
      run.steps, run.final.P, std::abs(run.final.P / ex.P - 1), run.final.L, std::abs(run.final.L - ex.L), run.final.t,
      std::abs(run.final.t / ex.t - 1));
  // The event is located on the RK4 map and the step control follows the exponential decay of L
  // at the end of erosion (L_end ~ 1e-3 L0 here), so the end state keeps the 4th order: at
  // 200 steps per L0/V0 the observed errors are ~1e-14 relative (1460 steps); 1e-10 leaves margin
  // for other compilers, and a fixed-step run fails it (0.5 % error in L_end without the step control).
  EXPECT_NEAR(run.final.P, ex.P, 1e-10 * ex.P);
  EXPECT_NEAR(run.final.L, ex.L, 1e-10 * in.L0);
  EXPECT_NEAR(run.final.t, ex.t, 1e-10 * ex.t);
  EXPECT_NEAR(run.final.V, std::sqrt(2 * (in.R - in.Y) / in.rho_p), 1e-9 * in.V0);
}

TEST(Tate, StrongRodErodesThenPenetratesRigidly) {
  // Y > R: erosion stops at rho_t V^2 / 2 = Y - R (U = V); the rod then penetrates as a rigid body.
  const bp::TateInput in{0.1, 17600, 2700, 0.5e9, 1.5e9, 1500};
  const auto run = bp::integrate_tate(in);
  EXPECT_EQ(run.stop_reason, "V = 0");
  const bp::TateState ex = bp::walters_segletes_final(in);
  const bp::TateState* onset = nullptr;
  for (const auto& s : run.history)
    if (s.rigid) {
      onset = &s;
      break;
    }
  ASSERT_NE(onset, nullptr);
  EXPECT_NEAR(onset->V, std::sqrt(2 * (in.Y - in.R) / in.rho_t), 1e-9 * in.V0);
  EXPECT_NEAR(onset->P, ex.P, 1e-8 * ex.P);
  EXPECT_NEAR(onset->L, ex.L, 1e-8 * in.L0);
  EXPECT_GT(run.final.P, onset->P);       // rigid penetration adds depth
  EXPECT_NEAR(run.final.L, onset->L, 0);  // a rigid rod does not erode
}

TEST(Tate, RejectsBadInput) {
  EXPECT_THROW(bp::integrate_tate({0, 17600, 7850, 5e9, 1.5e9, 1500}), ballista::Error);        // L0
  EXPECT_THROW(bp::integrate_tate({0.1, 17600, 7850, -1, 1.5e9, 1500}), ballista::Error);       // R < 0
  EXPECT_THROW(bp::integrate_tate({0.1, 17600, 7850, 0, 1.5e9, 1500}), ballista::Error);        // rigid, R = 0
  EXPECT_THROW(bp::walters_segletes_at_velocity(tungsten_into_steel(), 100), ballista::Error);  // past the end
}

TEST(Tate, ExactSolutionBranchesAgreeWithIntegration) {
  // The closed form of int (v - U) dv (rho_p != rho_t, both signs of 1 - mu^2 and of c) and the
  // quadrature branch near mu = 1 (rho_p = rho_t), each against RK4 at 200 steps per transit
  // (observed ~1e-13 in the tungsten case; 1e-9 relative leaves room for these harder cases).
  const bp::TateInput cases[] = {
      {0.1, 7850, 7850, 3e9, 1e9, 2000},       // mu = 1: quadrature branch
      {0.1, 2700, 7850, 3e9, 0.4e9, 2500},     // aluminium into steel: mu^2 > 1, c < 0
      {0.1, 17600, 2700, 0.5e9, 1.5e9, 1500},  // Y > R: 1 - mu^2 > 0, A < 0, ends at rigid onset
  };
  for (const auto& in : cases) {
    const bp::TateState ex = bp::walters_segletes_final(in);
    const auto run = bp::integrate_tate(in);
    const bp::TateState* end = &run.final;
    for (const auto& s : run.history)
      if (s.rigid) {
        end = &s;
        break;
      }
    EXPECT_NEAR(end->P, ex.P, 1e-9 * ex.P) << "rho_p " << in.rho_p;
    EXPECT_NEAR(end->L, ex.L, 1e-9 * in.L0) << "rho_p " << in.rho_p;
    EXPECT_NEAR(end->t, ex.t, 1e-9 * ex.t) << "rho_p " << in.rho_p;
  }
}

// Issue 11 regression (a hang): R = Y makes c = (1 - mu^2) A = 0 and the closed-form erosion
// integral took c ln(mu v + s) = 0 * ln 0 = NaN at v = 0, which made the quadrature tolerance NaN.
// With R = Y the interface is hydrodynamic, U = V/(1 + mu), mu = sqrt(rho_t/rho_p), so
// dL/dV = (dL/dt)/(dV/dt) = mu rho_p V L/((1 + mu) Y) and dP/dV = U rho_p L/Y; from V0 down to 0:
// L_f = L0 exp(-mu rho_p V0^2/(2 (1 + mu) Y)) and P = (L0 - L_f)/mu, the Birkhoff depth
// (thesis eq. 3.2) of the eroded length.
TEST(Tate, EqualStrengthsHaveClosedFormFinalState) {
  const bp::TateInput in{0.07354, 19235, 2300, 1e9, 1e9, 3300};
  const double mu = std::sqrt(in.rho_t / in.rho_p);
  const double Lf = in.L0 * std::exp(-mu * in.rho_p * in.V0 * in.V0 / (2 * (1 + mu) * in.Y));
  const bp::TateState ws = bp::walters_segletes_final(in);
  EXPECT_EQ(ws.V, 0.0);
  EXPECT_NEAR(ws.L, Lf, 1e-10 * Lf);  // closed-form erosion integral: round-off only
  EXPECT_NEAR(ws.P, (in.L0 - Lf) / mu, 1e-10 * in.L0);  // quadrature tolerance 1e-13 relative, summed
  // The RK4 integration stops too ("V = 0"), at the same depth to its step control's accuracy.
  const bp::TateRun run = bp::integrate_tate(in, {});
  EXPECT_NEAR(run.final.P, ws.P, 1e-4 * ws.P);
}

}  // namespace test_tate
