// Probe `mean_velocity`: a body's centre-of-mass velocity along an axis, sum m v / sum m (m/s):
// the velocity of a plate or case driven by explosive (Gurney), of a rod, of a fragment
// cloud.
#include <cmath>

#include "core/point_fields.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

class MeanVelocityProbe : public Probe {
 public:
  MeanVelocityProbe(int body, int axis) : body_(body), axis_(axis) {}

  double value(const ProbeContext& c) const override {
    const Index n = c.points.size();
    const auto* bid = c.points.ints(kBodyIndex);
    const auto* m = c.points.real(kMass);
    const auto* v = c.points.view(kVelocity);
    double s[2] = {0.0, 0.0};
    for (Index p = 0; p < n; ++p)
      if (body_ < 0 || bid[p] == body_) {
        s[0] += m[p] * v[p][axis_];
        s[1] += m[p];
      }
    c.comm.sum(s, 2);
    return s[1] > 0.0 ? s[0] / s[1] : std::nan("");
  }

 private:
  int body_;  // deck order, -1 = every body
  int axis_;
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "mean_velocity",
    .description = "the body's centre-of-mass velocity along `axis`, sum m v / sum m [m/s]",
    .params = {{.name = "body", .kind = ProbeParam::Kind::Body, .unit = "",
                .description = "body measured (default: every body)"},
               {.name = "axis", .kind = ProbeParam::Kind::Axis, .unit = "", .description = "velocity component"}},
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<MeanVelocityProbe>(probe_body(spec, sc), static_cast<int>(spec.params.at("axis")));
    }})

}  // namespace ballista
