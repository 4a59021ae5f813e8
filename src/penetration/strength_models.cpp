#include "penetration/strength_models.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/input_checks.hpp"

namespace ballista::penetration {

namespace {

/// The steady eroding jet of effective density k: U from the interface balance
/// k (V - U)^2 = rho_t U^2 + 2 sigma with sigma = R - Y (eq. 3.6-3.7), then the depth
/// P = L sqrt(k/rho_t - 2 sigma/(rho_t (V - U)^2)) (eq. 3.8). Eichelberger (k = lambda rho_p) and
/// Grove (k = rho_d (1 + phi), whose eq. 3.11-3.13 are eq. 3.6-3.8 with that k) are this one
/// calculation, so they share it. Throws in the rigid regime (U = V: the depth divides by V - U);
/// `rigid_note` ends that message with what does not apply for `model`.
SteadyPenetration steady_eroding_jet(const char* model, const char* rigid_note, double L, double k, double rho_t,
                                     double R, double Y, double V) {
  const double sigma = R - Y;  // eq. 3.7
  const InterfaceSolution s = solve_interface(k, rho_t, sigma, V);
  if (s.regime == InterfaceRegime::kNoPenetration) return {0.0, 0.0, s.regime};
  if (s.regime == InterfaceRegime::kRigid)
    throw Error(fmt::format("{}: rho_t V^2 = {:g} Pa <= 2 (Y - R) = {:g} Pa: the jet does not erode {}", model,
                            rho_t * V * V, 2 * (Y - R), rigid_note));
  const double w = V - s.U;
  // The argument equals (U/(V-U))^2 rho_t/rho_t by the balance, so it is >= 0 here.
  const double arg = k / rho_t - 2 * sigma / (rho_t * w * w);
  return {s.U, L * std::sqrt(std::max(arg, 0.0)), s.regime};
}

}  // namespace

double pack_evans_penalty(const PackEvansInput& in) {
  require_inputs("pack-evans", {positive("rho_p", in.rho_p, "kg/m^3"), positive("V", in.V, "m/s"),
                                non_negative("alpha", in.alpha, "1"), non_negative("sigma_y", in.sigma_y, "Pa")});
  return in.alpha * in.sigma_y / (in.rho_p * in.V * in.V);  // eq. 3.5, sigma_y / (rho_p V^2) scaled by alpha
}

double pack_evans_depth(const PackEvansInput& in) {
  require_inputs("pack-evans", {non_negative("L", in.L, "m"), positive("lambda", in.lambda, "1"),
                                positive("rho_t", in.rho_t, "kg/m^3"), non_negative("r", in.r, "m")});
  const double x = pack_evans_penalty(in);
  if (x > 1)
    throw Error(
        fmt::format("pack-evans: the penalty alpha sigma_y / (rho_p V^2) = {:g} exceeds 1: the strength "
                    "term of eq. 3.5 leaves no real depth (raise V or lower alpha, sigma_y)",
                    x));
  const double ratio = in.lambda * in.rho_p / in.rho_t;
  if (in.form == PackEvansForm::kPenaltyInsideRoot) return in.L * std::sqrt(ratio * (1 - x)) + in.r;  // eq. 3.5
  return in.L * std::sqrt(ratio) * (1 - x) + in.r;  // the form eq. 6.15-6.16 invert
}

SteadyPenetration eichelberger(const EichelbergerInput& in) {
  require_inputs("eichelberger", {non_negative("L", in.L, "m"), positive("lambda", in.lambda, "1"),
                                  positive("rho_p", in.rho_p, "kg/m^3"), positive("rho_t", in.rho_t, "kg/m^3"),
                                  finite("R", in.R, "Pa"), finite("Y", in.Y, "Pa"), non_negative("V", in.V, "m/s")});
  // eq. 3.6-3.8: the steady eroding jet with k = lambda rho_p.
  return steady_eroding_jet("eichelberger", "(U = V) and eq. 3.8 does not apply", in.L, in.lambda * in.rho_p, in.rho_t,
                            in.R, in.Y, in.V);
}

double gladkikh_depth(double L, double rho_p, double rho_t, double V_tip, double V_tail) {
  require_inputs("gladkikh", {non_negative("L", L, "m"), positive("rho_p", rho_p, "kg/m^3"),
                              positive("rho_t", rho_t, "kg/m^3"), positive("V_tail", V_tail, "m/s"),
                              positive("V_tip", V_tip, "m/s")});
  const double G = V_tip / V_tail;  // Gamma of eq. 3.10
  if (!(G > 1))
    throw Error(fmt::format("gladkikh: V_tip/V_tail = {:g} must be > 1: eq. 3.10 needs a velocity gradient", G));
  const double g = std::sqrt(rho_p / rho_t);                                        // gamma of eq. 3.10
  const double bracket = ((2 + g) * G - 2 * (1 + g) * std::sqrt(G + g)) / (G - 1);  // eq. 3.10
  if (!(bracket > 0))
    throw Error(
        fmt::format("gladkikh: eq. 3.10 gives no positive depth for V_tip/V_tail = {:g} and "
                    "sqrt(rho_p/rho_t) = {:g} (bracket {:g}); use a larger velocity ratio",
                    G, g, bracket));
  return L * g * bracket;
}

GroveResult grove(const GroveInput& in) {
  require_inputs("grove", {non_negative("L", in.L, "m"), positive("rho_d", in.rho_d, "kg/m^3"),
                           positive("rho_s", in.rho_s, "kg/m^3"), positive("rho_t", in.rho_t, "kg/m^3"),
                           finite("R", in.R, "Pa"), finite("Y", in.Y, "Pa"), non_negative("V", in.V, "m/s")});
  if (in.rho_d > in.rho_s)
    throw Error(
        fmt::format("grove: rho_d = {:g} must not exceed rho_s = {:g} [kg/m^3] (porosity >= 0)", in.rho_d, in.rho_s));
  const double phi = 1 - in.rho_d / in.rho_s;  // porosity, below eq. 3.12
  const double k = in.rho_d * (1 + phi);       // eq. 3.11 = eq. 3.12: k (V-U)^2 = rho_t U^2 + 2 sigma
  // eq. 3.13 is eq. 3.8 with this k: the steady eroding jet.
  return {phi, steady_eroding_jet("grove", "and eq. 3.13 does not apply", in.L, k, in.rho_t, in.R, in.Y, in.V)};
}

}  // namespace ballista::penetration
