// Probe `max_velocity`: the largest velocity component along an axis over a body's points (m/s):
// the tip of a shaped-charge jet, the fastest fragment, the leading edge of a spall layer. For
// motion towards -axis, `min_velocity` gives the most negative one.
#include <limits>

#include "analysis/body_probe.hpp"

namespace ballista {

namespace {

template <int Sign>
class ExtremeVelocityProbe : public BodyAxisProbe {
 public:
  using BodyAxisProbe::BodyAxisProbe;

  double value(const ProbeContext& c) const override {
    const auto* v = c.points.view(kVelocity);
    double m = -std::numeric_limits<double>::infinity();
    for_each_point(c.points, [&](Index p) { m = std::max(m, Sign * v[p][axis()]); });
    return Sign * max_over_ranks(m, c.comm);
  }
};

}  // namespace

BALLISTA_REGISTER_PROBE(body_axis_probe_factory<ExtremeVelocityProbe<1>>(
    "max_velocity", "the largest velocity component along `axis` over the body's points (a jet's tip) [m/s]", "m/s",
    "velocity component"))
BALLISTA_REGISTER_PROBE(body_axis_probe_factory<ExtremeVelocityProbe<-1>>(
    "min_velocity", "the smallest (most negative) velocity component along `axis` over the body's points [m/s]",
    "m/s", "velocity component"))

}  // namespace ballista
