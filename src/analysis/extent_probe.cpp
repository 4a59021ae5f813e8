// Probe `extent`: max - min of a body's deformed domains along an axis, m (e.g. a rod's length).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/body_probe.hpp"
#include "analysis/domain_corners.hpp"

namespace ballista {

namespace {

class ExtentProbe : public BodyAxisProbe {
 public:
  using BodyAxisProbe::BodyAxisProbe;

  double value(const ProbeContext& c) const override {
    const PointDomains domains(c.points, c.nd());
    double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
    for_each_point(c.points, [&](Index p) {
      domains.for_each_corner(p, [&](const Vec3& y) {
        lo = std::min(lo, y[axis()]);
        hi = std::max(hi, y[axis()]);
      });
    });
    lo = c.comm.min(lo);
    hi = c.comm.max(hi);
    return hi >= lo ? hi - lo : std::nan("");
  }
};

}  // namespace

BALLISTA_REGISTER_PROBE(body_axis_probe_factory<ExtentProbe>(
    "extent", "max - min of the body's deformed particle domains along `axis` [m]", "m", "axis measured"))

}  // namespace ballista
