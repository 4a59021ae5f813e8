// Probe `radial_velocity`: a body's mass-weighted mean velocity away from an axis,
// sum m (v . e_r) / sum m (m/s): the expansion velocity of a cylinder case driven by explosive
// (Gurney's cylinder, the seed's exploding cylinders), where the centre-of-mass velocity
// is zero by symmetry.
#include "analysis/body_probe.hpp"

namespace ballista {

namespace {

class RadialVelocityProbe : public BodyAxisProbe {
 public:
  RadialVelocityProbe(int body, int axis, const Vec3& center) : BodyAxisProbe(body, axis), center_(center) {}

  double value(const ProbeContext& c) const override {
    const int nd = c.nd();
    const auto* m = c.points.real(kMass);
    const auto* x = c.points.view(kPosition);
    const auto* v = c.points.view(kVelocity);
    double s[2] = {0.0, 0.0};
    for_each_point(c.points, [&](Index p) {
      // e_r: the point's offset from the axis, its component along the axis removed (in 2D the
      // axis is normal to the plane when it is z).
      Vec3 r = x[p] - center_;
      if (axis() < nd) r[axis()] = 0.0;
      if (nd == 2) r[2] = 0.0;
      const double len = norm(r);
      if (len == 0.0) return;
      s[0] += m[p] * dot(v[p], r) / len;
      s[1] += m[p];
    });
    return mass_weighted_mean(s, c.comm);
  }

 private:
  Vec3 center_;
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "radial_velocity",
    .description = "the body's mass-weighted mean velocity away from the axis through `center` along `axis` "
                   "(a cylinder's expansion velocity), sum m v.e_r / sum m [m/s]",
    .unit = "m/s",
    .params = {body_param(), axis_param("the cylinder's axis"),
               axis_point_param("a point on the axis (default: the origin)")},
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<RadialVelocityProbe>(probe_body(spec, sc), probe_axis(spec), spec.vectors.at("center"));
    }})

}  // namespace ballista
