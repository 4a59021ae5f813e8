// CATALOGUE A7 through the single-element driver (problem: a7_misaligned_rate.hpp).
//
// Tolerance. The exact solution (j2_deviatoric_legs.hpp) has no step error; a radial return has.
// With delta = 2G |de_step| / R, the step's deviatoric increment measured in yield strains, one
// return maps the angle psi of s from the rate to atan2(sin psi, cos psi + delta) = psi - delta
// sin psi + delta^2 sin psi cos psi + O(delta^3), where the exact flow gives psi - delta sin psi +
// (delta^2 / 2) sin psi cos psi: a local error (delta^2 / 2) sin psi cos psi. Per unit of
// x = 2G |de| tau / R the angle error e then obeys de/dx = -cos psi e + (delta / 2) sin psi cos psi
// with d psi/dx = -sin psi; in psi this integrates to e = (delta / 2) sin psi ln(sin psi0 / sin psi),
// whose largest value over the turn is (delta / 2) sin psi0 / e (Euler's number e). So each leg that
// flows from psi0 adds at most (delta_leg / 2) sin psi0 / e to the angle (0.16 delta on leg 2 from
// 60 degrees, 0.09 delta on leg 3 from 30 degrees), and the stress error is R times the angle.
// The tolerance is 1.5 x the sum over the legs (the legs' errors add at worst; the bound is the
// leading term in delta): first order, so it halves with the step (asserted too), and it catches
// a return that is off by a fixed fraction (a mis-scaled radius; a return along the rate instead of
// the radius), whose error does not shrink with the step. The strain-measure drift (midpoint
// increments against ln of the log-linear steps, (d e)^3 / 12 per step) is ~1e-20: negligible.
#include "verify/a7_misaligned_rate.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "driver/point_driver.hpp"
#include "verify/hook_material.hpp"
#include "verify/j2_deviatoric_legs.hpp"

namespace ballista {

namespace {

const double kPi = 3.14159265358979323846;

DriveResult drive(const Material& m, const std::vector<std::array<double, 3>>& legs, int steps) {
  DriveProgram prog;
  for (const auto& l : legs) {
    DriveLeg g;
    g.duration = 1.0;
    g.steps = steps;
    g.value = {l[0], l[1], l[2], 0.0, 0.0, 0.0};
    prog.legs.push_back(g);
  }
  return drive_point(m, prog);
}

/// The run against the exact solution, record by record.
struct A7Run {
  std::vector<double> t, s1, s2, s1_an, s2_an, s11, s22, s33, s11_an, s22_an, s33_an;
  double max_error = 0.0;   ///< max |sigma - exact|_F / R
  double off_circle = 0.0;  ///< max ||s| - R| / R on steps the exact solution is plastic
  double end_angle_leg2 = 0.0, end_angle_leg2_an = 0.0;  ///< angle of s from leg 2's rate at its end, degrees
};

double angle_between(const Dev2& a, const Dev2& b) {
  return std::atan2(a[0] * b[1] - a[1] * b[0], a[0] * b[0] + a[1] * b[1]) * 180.0 / kPi;
}

A7Run compare(const DriveResult& r, const J2DeviatoricLegs& exact, const std::vector<std::array<double, 3>>& legs,
              int steps, double R) {
  A7Run out;
  for (size_t k = 0; k < r.records.size(); ++k) {
    const DriveRecord& rec = r.records[k];
    // Record k > 0 ends step k: leg (k - 1) / steps, fraction of it ((k - 1) % steps + 1) / steps.
    const size_t leg = k == 0 ? 0 : (k - 1) / steps;
    const double tau = k == 0 ? 0.0 : static_cast<double>((k - 1) % steps + 1) / steps;
    const std::array<double, 3> an = exact.stress(leg, tau);
    const Mat3& s = rec.sigma;
    const Mat3 diff = s - Mat3::diag(an[0], an[1], an[2]);
    out.max_error = std::max(out.max_error, frobenius(diff) / R);
    const Dev2 dev = deviatoric_components({s(0, 0), s(1, 1), s(2, 2)});
    const Dev2 dev_an = exact.deviator(leg, tau);
    if (k > 0 && tau > exact.yield_fraction(leg))
      out.off_circle = std::max(out.off_circle, std::abs(std::hypot(dev[0], dev[1]) - R) / R);
    if (k == 2 * static_cast<size_t>(steps)) {
      const Dev2 rate = deviatoric_components(legs[1]);
      out.end_angle_leg2 = angle_between(rate, dev);
      out.end_angle_leg2_an = angle_between(rate, dev_an);
    }
    out.t.push_back(rec.t);
    out.s1.push_back(dev[0]);
    out.s2.push_back(dev[1]);
    out.s1_an.push_back(dev_an[0]);
    out.s2_an.push_back(dev_an[1]);
    out.s11.push_back(s(0, 0));
    out.s22.push_back(s(1, 1));
    out.s33.push_back(s(2, 2));
    out.s11_an.push_back(an[0]);
    out.s22_an.push_back(an[1]);
    out.s33_an.push_back(an[2]);
  }
  return out;
}

}  // namespace

std::vector<std::array<double, 3>> A7Problem::legs() const {
  auto deviatoric = [](double norm, double angle_deg, double volume) {
    const double a = angle_deg * kPi / 180.0;
    const Dev2 s{norm * std::cos(a), norm * std::sin(a)};
    return diagonal_of(s, volume / 3.0);
  };
  return {{uniaxial, 0.0, 0.0}, deviatoric(leg2_norm, leg2_angle_deg, leg2_volume),
          deviatoric(leg3_norm, leg3_angle_deg, leg3_volume)};
}

VerifyCase run_a7(const MaterialFactory& f, const A7Problem& pb) {
  const std::string id = "A7";
  const std::string title =
      "A7 J2 under a strain rate misaligned with the yield normal, fixed eigenvectors (Brannon & Leelavanichkul "
      "2010; exact: Krieg & Krieg 1977): K = 79 GPa, G = 70 GPa, tau_y = 165 MPa, perfect plasticity";
  if (!f.reduce_j2)
    return VerifyCase::not_applicable(f.model, id, title, "model has no reduce_j2 hook (reduction to J2 plasticity)");
  const ParamValues v = f.reduce_j2(pb.density, pb.bulk, pb.shear, std::sqrt(3.0) * pb.tau_y, 0.0, 0.0);
  if (v.empty() && v.choices.empty())
    return VerifyCase::not_applicable(f.model, id, title, "reduce_j2 returns no parameters for perfect plasticity");
  VerifyCase c = VerifyCase::begin(f.model, id, title, "a7");
  const auto mat = make_hook_material(f, v, "reduce_j2");
  const J2PerfectParams jp{pb.bulk, pb.shear, pb.tau_y};
  const double R = jp.radius();
  const std::vector<std::array<double, 3>> legs = pb.legs();
  const J2DeviatoricLegs exact(jp, legs);

  const A7Run run = compare(drive(*mat, legs, pb.steps), exact, legs, pb.steps, R);
  const A7Run half = compare(drive(*mat, legs, pb.steps / 2), exact, legs, pb.steps / 2, R);
  const A7Run quarter = compare(drive(*mat, legs, pb.steps / 4), exact, legs, pb.steps / 4, R);
  const double order = std::log2(half.max_error / run.max_error);
  const double order_coarse = std::log2(quarter.max_error / half.max_error);

  // Sum over the legs of the radial return's error bound (delta_leg / 2) sin psi0 / e (top of file).
  double bound = 0.0;
  for (size_t l = 0; l < legs.size(); ++l) {
    const Dev2 de = deviatoric_components(legs[l]);
    const double delta = 2.0 * pb.shear * std::hypot(de[0], de[1]) / (R * pb.steps);
    bound += 0.5 * delta * std::abs(std::sin(exact.yield_angle(l))) / std::exp(1.0);
  }
  const double tol = 1.5 * bound;
  c.max_rel_error = run.max_error;
  c.tolerance = tol;
  c.error_measure = "max over all steps of |sigma - exact|_F / R, R = sqrt2 tau_y the yield circle's radius; exact = "
                    "closed form in the legs' log strain (elastic line, then tan(psi/2) ~ exp(-2G|de| tau / R))";
  c.tolerance_justification = fmt::format(
      "1.5 x {:.3g}, the sum over the legs of a radial return's leading error (delta / 2) sin psi0 / e, delta = "
      "2G |de_step| / R the step's increment in yield strains and psi0 the angle from the rate where the leg starts "
      "to flow; first order, so it halves with the step (asserted)",
      bound);
  c.check("stresses vs the exact solution (|sigma - exact|_F / R)", run.max_error, tol);
  c.check(fmt::format("first order in the step: log2(error(N/2) / error(N)) (errors {:.3g}, {:.3g}, {:.3g} at N/4, "
                      "N/2, N)",
                      quarter.max_error, half.max_error, run.max_error),
          run.max_error < 1e-9 ? 1.0 : order, 0.8, true);
  c.check("on the yield circle on plastic steps: max ||s| - R| / R (a return ends on the surface)", run.off_circle,
          1e-8);
  c.check(fmt::format("leg 2 turns towards its rate: angle of s from the rate at its end, exact {:.3f} deg; "
                      "|difference| in degrees",
                      run.end_angle_leg2_an),
          std::abs(run.end_angle_leg2 - run.end_angle_leg2_an), tol * 180.0 / kPi);

  const int e = pb.plot_every;
  const std::pair<const char*, const std::vector<double>*> plotted[] = {
      {"t", &run.t},         {"s1", &run.s1},   {"s2", &run.s2},   {"s1_an", &run.s1_an},
      {"s2_an", &run.s2_an}, {"s11", &run.s11}, {"s22", &run.s22}, {"s33", &run.s33},
      {"s11_an", &run.s11_an}, {"s22_an", &run.s22_an}, {"s33_an", &run.s33_an}};
  for (const auto& [name, series] : plotted) c.series.push_back({name, every_nth(*series, e)});
  c.scalars = {{"radius", R},
               {"error_bound", bound},
               {"steps_per_leg", static_cast<double>(pb.steps)},
               {"error_quarter_steps", quarter.max_error},
               {"error_half_steps", half.max_error},
               {"error", run.max_error},
               {"convergence_order", order},
               {"convergence_order_coarse", order_coarse},
               {"leg3_yield_fraction", exact.yield_fraction(2)},
               {"leg2_end_angle_deg", run.end_angle_leg2},
               {"leg2_end_angle_an_deg", run.end_angle_leg2_an}};
  c.finish();
  return c;
}

}  // namespace ballista
