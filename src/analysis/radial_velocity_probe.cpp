// Probe `radial_velocity`: a body's mass-weighted mean velocity away from an axis,
// sum m (v . e_r) / sum m (m/s): the expansion velocity of a cylinder case driven by explosive
// (Gurney's cylinder, the seed's exploding cylinders), where the centre-of-mass velocity
// is zero by symmetry.
#include <cmath>

#include "core/point_fields.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

class RadialVelocityProbe : public Probe {
 public:
  RadialVelocityProbe(int body, int axis, const Vec3& center) : body_(body), axis_(axis), center_(center) {}

  double value(const ProbeContext& c) const override {
    const int nd = c.dim == Dimension::ThreeD ? 3 : 2;
    const Index n = c.points.size();
    const auto* bid = c.points.ints(kBodyIndex);
    const auto* m = c.points.real(kMass);
    const auto* x = c.points.view(kPosition);
    const auto* v = c.points.view(kVelocity);
    double s[2] = {0.0, 0.0};
    for (Index p = 0; p < n; ++p) {
      if (body_ >= 0 && bid[p] != body_) continue;
      // e_r: the point's offset from the axis, its component along the axis removed (in 2D the
      // axis is normal to the plane when it is z).
      Vec3 r = x[p] - center_;
      if (axis_ < nd) r[axis_] = 0.0;
      if (nd == 2) r[2] = 0.0;
      const double len = norm(r);
      if (len == 0.0) continue;
      s[0] += m[p] * dot(v[p], r) / len;
      s[1] += m[p];
    }
    c.comm.sum(s, 2);
    return s[1] > 0.0 ? s[0] / s[1] : std::nan("");
  }

 private:
  int body_;  // deck order, -1 = every body
  int axis_;
  Vec3 center_;
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "radial_velocity",
    .description = "the body's mass-weighted mean velocity away from the axis through `center` along `axis` "
                   "(a cylinder's expansion velocity), sum m v.e_r / sum m [m/s]",
    .params = {{.name = "body", .kind = ProbeParam::Kind::Body, .unit = "",
                .description = "body measured (default: every body)"},
               {.name = "axis", .kind = ProbeParam::Kind::Axis, .unit = "", .description = "the cylinder's axis"},
               {.name = "center", .kind = ProbeParam::Kind::Vector, .unit = "m",
                .description = "a point on the axis (default: the origin)", .required = false}},
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<RadialVelocityProbe>(probe_body(spec, sc), static_cast<int>(spec.params.at("axis")),
                                                   spec.vectors.at("center"));
    }})

}  // namespace ballista
