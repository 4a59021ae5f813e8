#include "penetration/walters_segletes.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/quadrature.hpp"

namespace ballista::penetration {

namespace {

constexpr double kRelTol = 1e-13;  // quadrature tolerance relative to a first estimate

struct Exact {
  const TateInput& in;
  double mu2, mu, A, c;
  explicit Exact(const TateInput& i)
      : in(i), mu2(i.rho_t / i.rho_p), mu(std::sqrt(mu2)), A(2 * (i.R - i.Y) / i.rho_p), c((1 - mu2) * A) {}

  double s(double v) const { return std::sqrt(std::max(mu2 * v * v + c, 0.0)); }
  double U(double v) const { return tate_penetration_velocity(in, v).U; }

  /// int_V^V0 (v - U(v)) dv (header: closed form, or quadrature near mu = 1).
  double erosion_integral(double V) const {
    if (std::abs(1 - mu2) >= 1e-3) {
      auto F = [&](double v) {
        const double sv = s(v);
        // c ln(mu v + s) -> 0 as c -> 0 (R = Y: s = mu v, and ln 0 at v = 0 would give 0 * inf = NaN).
        const double log_term = c == 0 ? 0.0 : c / (2 * mu) * std::log(mu * v + sv);
        return (v * sv / 2 + log_term - mu2 * v * v / 2) / (1 - mu2);
      };
      return F(in.V0) - F(V);
    }
    auto w = [&](double v) {
      const double sv = s(v);
      return (v * sv + A) / (v + sv);
    };  // = v - U(v)
    return quad(w, V, in.V0);
  }
  /// L(V) = L0 exp(-(rho_p/Y) int_V^V0 (v - U) dv).
  double L(double V) const { return in.L0 * std::exp(-in.rho_p / in.Y * erosion_integral(V)); }

  template <class F>
  double quad(const F& f, double a, double b) const {
    if (a == b) return 0;
    const double scale = std::abs((b - a) / 6 * (f(a) + 4 * f(0.5 * (a + b)) + f(b)));
    return integrate_adaptive_simpson(f, a, b, kRelTol * std::max(scale, 1e-300));
  }

  TateState at(double V) const {
    const double k = in.rho_p / in.Y;
    TateState st;
    st.V = V;
    st.U = U(V);
    st.L = L(V);
    st.P = k * quad([&](double v) { return L(v) * U(v); }, V, in.V0);
    st.t = k * quad([&](double v) { return L(v); }, V, in.V0);
    return st;
  }
};

}  // namespace

double walters_segletes_final_velocity(const TateInput& in) {
  validate(in);
  if (in.Y == 0) return in.V0;
  const double A = 2 * (in.R - in.Y) / in.rho_p;
  if (A > 0) return std::sqrt(A);                             // U = 0: eq. 3.9 with U = 0
  if (A < 0) return std::sqrt(2 * (in.Y - in.R) / in.rho_t);  // U = V: eq. 3.9 with U = V
  return 0;
}

TateState walters_segletes_at_velocity(const TateInput& in, double V) {
  validate(in);
  if (!(in.Y > 0)) throw Error("walters-segletes: Y must be > 0 (with Y = 0 the rod velocity is constant)");
  const double V_end = walters_segletes_final_velocity(in);
  if (!(V >= V_end && V <= in.V0))
    throw Error(
        fmt::format("walters-segletes: V = {:g} m/s outside the eroding phase [{:g}, {:g}] m/s", V, V_end, in.V0));
  return Exact(in).at(V);
}

TateState walters_segletes_final(const TateInput& in) {
  return walters_segletes_at_velocity(in, walters_segletes_final_velocity(in));
}

TateState walters_segletes_at_time(const TateInput& in, double t) {
  validate(in);
  if (in.Y == 0) {  // V constant: every quantity is linear in t until L = 0
    const double U = tate_penetration_velocity(in, in.V0).U;
    const double L = in.L0 - (in.V0 - U) * t;
    if (L < 0) throw Error(fmt::format("walters-segletes: t = {:g} s after the rod is consumed", t));
    return {t, in.V0, U, L, U * t, false};
  }
  const Exact ex(in);
  const double V_end = walters_segletes_final_velocity(in);
  const TateState end = ex.at(V_end);
  if (t > end.t)
    throw Error(fmt::format("walters-segletes: t = {:g} s after the end of the eroding phase at {:g} s", t, end.t));
  // Newton on t(V) = t, dt/dV = -rho_p L(V)/Y, safeguarded by the bracket [V_end, V0].
  double lo = V_end, hi = in.V0, V = in.V0 - (in.V0 - V_end) * t / end.t;
  for (int it = 0; it < 100; ++it) {
    const double tv = ex.at(V).t;
    if (tv > t)
      lo = V;
    else
      hi = V;
    double next = V + (tv - t) * in.Y / (in.rho_p * ex.L(V));
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - V) <= 1e-14 * in.V0) {
      V = next;
      break;
    }
    V = next;
  }
  return ex.at(V);
}

}  // namespace ballista::penetration
