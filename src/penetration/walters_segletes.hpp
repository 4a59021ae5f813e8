#pragma once
// Exact solution of the eroding phase of the Alekseevskii-Tate equations (tate.hpp), after
// Walters & Segletes, "An exact solution of the long rod penetration equations", Int. J. Impact
// Eng. 11 (1991) 225-231: with the rod velocity V as the independent variable (dV/dt = -Y/(rho_p L)),
//     dL/dV = rho_p L (V - U(V)) / Y   =>  L(V) = L0 exp(-(rho_p/Y) int_V^V0 (v - U(v)) dv)
// in closed form (below), and depth and time are single integrals of closed-form integrands,
//     P(V) = (rho_p/Y) int_V^V0 L(v) U(v) dv,     t(V) = (rho_p/Y) int_V^V0 L(v) dv,
// evaluated here by adaptive Simpson quadrature to a relative tolerance of 1e-13.
// With mu^2 = rho_t/rho_p, A = 2 (R - Y)/rho_p, c = (1 - mu^2) A, s(v) = sqrt(mu^2 v^2 + c):
//     v - U(v) = (s - mu^2 v) / (1 - mu^2),
//     int (v - U) dv = [v s / 2 + c/(2 mu) ln(mu v + s) - mu^2 v^2 / 2] / (1 - mu^2)   (mu != 1).
// Near mu = 1 (|1 - mu^2| < 1e-3) this difference cancels; int (v - U) dv is then also taken by
// quadrature of the cancellation-free (v s + A)/(v + s). Y = 0 has V constant: L = L0 - (V-U) t.
#include "penetration/tate.hpp"

namespace ballista::penetration {

/// Rod velocity at which the eroding phase ends: sqrt(A) if R > Y (U = 0), the onset of rigid
/// penetration sqrt(2 (Y - R)/rho_t) if Y > R, 0 if R = Y. Y = 0 erodes at constant V0 (returns V0).
double walters_segletes_final_velocity(const TateInput& in);

/// Exact state when the rod velocity has fallen to V (walters_segletes_final_velocity <= V <= V0;
/// Y > 0).
TateState walters_segletes_at_velocity(const TateInput& in, double V);

/// Exact state at time t of the eroding phase (Newton on t(V) = t); throws past its end.
TateState walters_segletes_at_time(const TateInput& in, double t);

/// Exact state at the end of the eroding phase (Y > 0).
TateState walters_segletes_final(const TateInput& in);

}  // namespace ballista::penetration
