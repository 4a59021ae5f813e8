#include "penetration/tate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "penetration/input_checks.hpp"

namespace ballista::penetration {

void validate(const TateInput& in) {
  require_inputs("tate", {positive("L", in.L0, "m"), positive("rho_p", in.rho_p, "kg/m^3"),
                          positive("rho_t", in.rho_t, "kg/m^3"), non_negative("R", in.R, "Pa"),
                          non_negative("Y", in.Y, "Pa"), positive("V", in.V0, "m/s")});
  // A rigid rod (Y > R) decelerates as dV/dt = -(R + rho_t V^2/2)/(rho_p L): with R = 0 it never stops.
  if (in.Y > in.R && !(in.R > 0))
    throw Error(
        fmt::format("tate: R = {:g} Pa must be > 0 when Y = {:g} Pa > R (the rigid rod would never stop)", in.R, in.Y));
}

InterfaceSolution tate_penetration_velocity(const TateInput& in, double V) {
  return solve_interface(in.rho_p, in.rho_t, in.R - in.Y, V);  // eq. 3.9 with k = rho_p, sigma = R - Y
}

namespace {

using Vec = std::array<double, 3>;  // V, L, P

struct Rhs {
  const TateInput& in;
  bool rigid;
  Vec operator()(const Vec& y) const {
    const double V = std::max(y[0], 0.0), L = std::max(y[1], 0.0);
    if (rigid)  // rigid rod (Tate 1967): target resistance plus stagnation pressure decelerate it
      return {-(in.R + 0.5 * in.rho_t * V * V) / (in.rho_p * L), 0.0, V};
    const double U = tate_penetration_velocity(in, V).U;
    // rod deceleration, erosion kinematics, penetration definition (header). L -> 0 only if Y = 0.
    return {L > 0 ? -in.Y / (in.rho_p * L) : 0.0, -(V - U), U};
  }
};

Vec rk4_step(const Rhs& f, const Vec& y, double h) {
  auto axpy = [](const Vec& a, double s, const Vec& b) {
    return Vec{a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
  };
  const Vec k1 = f(y), k2 = f(axpy(y, h / 2, k1)), k3 = f(axpy(y, h / 2, k2)), k4 = f(axpy(y, h, k3));
  Vec out;
  for (int i = 0; i < 3; ++i) out[i] = y[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  return out;
}

enum class Event { kNone, kUZero, kLZero, kRigidOnset, kVZero, kTEnd };

}  // namespace

TateRun integrate_tate(const TateInput& in, const TateOptions& opt) {
  validate(in);
  const double dt = opt.dt > 0 ? opt.dt : in.L0 / in.V0 / std::max(opt.steps_per_transit, 1);
  const double A = 2 * (in.R - in.Y) / in.rho_p, mu2 = in.rho_t / in.rho_p;
  // Event functions, positive while the current phase goes on.
  auto g_u = [&](const Vec& y) { return y[0] * y[0] - A; };            // U > 0 (R > Y)
  auto g_rigid = [&](const Vec& y) { return mu2 * y[0] * y[0] + A; };  // V - U > 0 (Y > R)
  auto g_l = [](const Vec& y) { return y[1]; };
  auto g_v = [](const Vec& y) { return y[0]; };

  TateRun run;
  Vec y{in.V0, in.L0, 0.0};
  double t = 0;
  const InterfaceSolution s0 = tate_penetration_velocity(in, in.V0);
  bool rigid = s0.regime == InterfaceRegime::kRigid;
  auto state = [&](const Vec& z, double time) {
    TateState st{time, z[0], rigid ? z[0] : tate_penetration_velocity(in, std::max(z[0], 0.0)).U, z[1], z[2], rigid};
    return st;
  };
  if (opt.record_history) run.history.push_back(state(y, t));
  if (s0.regime == InterfaceRegime::kNoPenetration) {
    run.final = state(y, t);
    run.stop_reason = "U = 0";
    return run;
  }
  while (run.steps < opt.max_steps) {
    const Rhs f{in, rigid};
    // Step control: the nominal dt, but at most 1/steps_per_transit of the time over which the
    // current rates would consume the rod (L/|dL/dt|) or stop it (V0/|dV/dt|). Near the end of
    // erosion L decays exponentially and dV/dt ~ 1/L grows; a fixed dt would lose accuracy there.
    // Every limit scales with 1/steps_per_transit, so halving it halves every step (order studies).
    const Vec rate = f(y);
    const double n = std::max(opt.steps_per_transit, 1);
    double h = dt;
    // (With Y = 0 the rod is consumed at a constant rate, RK4 is exact, and L reaches 0: no limit.)
    if (in.Y > 0 && rate[1] < 0 && y[1] > 0) h = std::min(h, y[1] / -rate[1] / n);
    if (rate[0] < 0) h = std::min(h, in.V0 / -rate[0] / n);
    h = std::min(h, opt.t_end - t);
    const Vec trial = rk4_step(f, y, h);
    // Which event, if any, this step crosses (the first in the step is found by bisection below).
    auto crossed = [&](const Vec& z, double hz) {
      if (t + hz >= opt.t_end) return Event::kTEnd;
      if (rigid) return g_v(z) <= 0 ? Event::kVZero : Event::kNone;
      if (A > 0 && g_u(z) <= 0) return Event::kUZero;
      if (A < 0 && g_rigid(z) <= 0) return Event::kRigidOnset;
      if (g_l(z) <= 0) return Event::kLZero;
      if (A == 0 && g_v(z) <= 0) return Event::kVZero;
      return Event::kNone;
    };
    Event ev = crossed(trial, h);
    if (ev == Event::kNone) {
      y = trial;
      t += h;
      ++run.steps;
      if (opt.record_history) run.history.push_back(state(y, t));
      continue;
    }
    double h_hit = h;
    if (ev != Event::kTEnd) {
      // Shorten the step to land on the event: bisection on the step length (the event function
      // of the RK4 map is monotone in h over one step of a decelerating rod).
      double lo = 0, hi = h;
      for (int it = 0; it < 200 && hi - lo > 1e-15 * std::max(h, 1e-300); ++it) {
        const double mid = 0.5 * (lo + hi);
        (crossed(rk4_step(f, y, mid), mid) == Event::kNone ? lo : hi) = mid;
      }
      h_hit = hi;
      ev = crossed(rk4_step(f, y, h_hit), h_hit);
      if (ev == Event::kNone) ev = Event::kTEnd;  // cannot happen: hi always crosses
    }
    y = rk4_step(f, y, h_hit);
    t += h_hit;
    ++run.steps;
    if (ev == Event::kRigidOnset) {
      rigid = true;  // eroding -> rigid: continue with the rigid-body equations
      if (opt.record_history) run.history.push_back(state(y, t));
      continue;
    }
    y[0] = std::max(y[0], 0.0);
    y[1] = std::max(y[1], 0.0);
    run.final = state(y, t);
    if (ev == Event::kUZero) run.final.U = 0;
    if (opt.record_history) run.history.push_back(run.final);
    run.stop_reason = ev == Event::kUZero   ? "U = 0"
                      : ev == Event::kLZero ? "L = 0"
                      : ev == Event::kVZero ? "V = 0"
                                            : "t_end";
    return run;
  }
  throw Error(
      fmt::format("tate: no end of penetration after {} steps of {:g} s (raise max_steps or dt)", opt.max_steps, dt));
}

}  // namespace ballista::penetration
