// Probe `mean_velocity`: a body's centre-of-mass velocity along an axis, sum m v / sum m (m/s):
// the velocity of a plate or case driven by explosive (Gurney), of a rod, of a fragment
// cloud.
#include "analysis/body_probe.hpp"

namespace ballista {

namespace {

class MeanVelocityProbe : public BodyAxisProbe {
 public:
  using BodyAxisProbe::BodyAxisProbe;

  double value(const ProbeContext& c) const override {
    const auto* m = c.points.real(kMass);
    const auto* v = c.points.view(kVelocity);
    double s[2] = {0.0, 0.0};
    for_each_point(c.points, [&](Index p) {
      s[0] += m[p] * v[p][axis()];
      s[1] += m[p];
    });
    return mass_weighted_mean(s, c.comm);
  }
};

}  // namespace

BALLISTA_REGISTER_PROBE(body_axis_probe_factory<MeanVelocityProbe>(
    "mean_velocity", "the body's centre-of-mass velocity along `axis`, sum m v / sum m [m/s]", "m/s",
    "velocity component"))

}  // namespace ballista
