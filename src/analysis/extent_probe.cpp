// Probe `extent`: max - min of a body's deformed domains along an axis, m (e.g. a rod's length).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/domain_corners.hpp"
#include "core/point_fields.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

class ExtentProbe : public Probe {
 public:
  ExtentProbe(int body, int axis) : body_(body), axis_(axis) {}

  double value(const ProbeContext& c) const override {
    const int nd = c.dim == Dimension::ThreeD ? 3 : 2;
    const Index n = c.points.size();
    const auto* bid = c.points.ints(kBodyIndex);
    const auto* x = c.points.view(kPosition);
    const auto* F = c.points.view(kDeformationGradient);
    const auto* half = c.points.view(kHalfSize);
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
    for (Index p = 0; p < n; ++p) {
      if (body_ >= 0 && bid[p] != body_) continue;
      for_each_corner(x[p], F[p], half[p], nd, [&](const Vec3& y) {
        lo = std::min(lo, y[axis_]);
        hi = std::max(hi, y[axis_]);
      });
    }
    lo = c.comm.min(lo);
    hi = c.comm.max(hi);
    return hi >= lo ? hi - lo : std::nan("");
  }

 private:
  int body_;  // deck order, -1 = every body
  int axis_;
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "extent",
    .description = "max - min of the body's deformed particle domains along `axis` [m]",
    .params = {{.name = "body", .kind = ProbeParam::Kind::Body, .unit = "",
                .description = "body measured (default: every body)"},
               {.name = "axis", .kind = ProbeParam::Kind::Axis, .unit = "", .description = "axis measured"}},
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<ExtentProbe>(probe_body(spec, sc), static_cast<int>(spec.params.at("axis")));
    }})

}  // namespace ballista
