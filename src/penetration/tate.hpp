#pragma once
// Alekseevskii-Tate long-rod penetration (thesis seed 000 eq. 3.9; Alekseevskii 1966, Tate 1967),
// steady and integrated in time with rod erosion:
//     rho_p L dV/dt = -Y                       (rod deceleration)
//     dL/dt = -(V - U)                         (erosion)
//     dP/dt = U                                (penetration)
//     Y + rho_p (V-U)^2 / 2 = rho_t U^2 / 2 + R   (eq. 3.9, interface)
// If Y > R the rod stops eroding once rho_t V^2 / 2 + R <= Y and then penetrates as a rigid body
// (Tate 1967): rho_p L dV/dt = -(R + rho_t V^2 / 2), dL/dt = 0, dP/dt = V.
// SI units: m, s, kg/m^3, Pa.
#include <string>
#include <vector>

#include "penetration/interface_balance.hpp"

namespace ballista::penetration {

struct TateInput {
  double L0 = 0;     ///< initial rod length [m]
  double rho_p = 0;  ///< rod density [kg/m^3]
  double rho_t = 0;  ///< target density [kg/m^3]
  double R = 0;      ///< target resistance [Pa], >= 0
  double Y = 0;      ///< rod dynamic strength [Pa], >= 0
  double V0 = 0;     ///< impact velocity [m/s]
};

/// Throws ballista::Error naming the first parameter out of range.
void validate(const TateInput& in);

/// Steady penetration velocity of eq. 3.9 at rod velocity V (the quadratic's closed form,
/// interface_balance.hpp with k = rho_p and sigma = R - Y).
InterfaceSolution tate_penetration_velocity(const TateInput& in, double V);

struct TateState {
  double t = 0;        ///< time since impact [s]
  double V = 0;        ///< rod (tail) velocity [m/s]
  double U = 0;        ///< penetration velocity [m/s]
  double L = 0;        ///< rod length [m]
  double P = 0;        ///< depth [m]
  bool rigid = false;  ///< true once the rod no longer erodes (Y > R only)
};

struct TateOptions {
  /// Nominal time step [s]; 0: L0 / V0 / steps_per_transit.
  double dt = 0;
  int steps_per_transit = 200;
  /// Stop at this time even if penetration goes on [s] (used to compare at a fixed time).
  double t_end = 1e300;
  long max_steps = 10'000'000;
  bool record_history = true;
};

struct TateRun {
  std::vector<TateState> history;  ///< every accepted step (if record_history), first = impact
  TateState final;
  long steps = 0;
  /// Why it stopped: "U = 0" (target too strong for the rod left), "L = 0" (rod consumed),
  /// "V = 0" (rigid rod stopped; or eroding rod stopped, R = Y), "t_end".
  std::string stop_reason;
};

/// Classical fourth-order Runge-Kutta with a fixed nominal step; the step that crosses an event
/// (U = 0, L = 0, onset of rigid penetration, V = 0, t_end) is shortened so the event is hit to
/// round-off (bisection on the step length of the same RK4 map), so the event time and the final
/// state keep the fourth order of the scheme.
TateRun integrate_tate(const TateInput& in, const TateOptions& options = {});

}  // namespace ballista::penetration
