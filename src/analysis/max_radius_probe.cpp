// Probe `max_radius`: the largest distance from a symmetry axis of the deformed domains of the
// particles near a plane normal to it, m (e.g. the mushroomed radius of a rod's head).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/axis_distance.hpp"
#include "analysis/body_probe.hpp"
#include "analysis/domain_corners.hpp"
#include "core/error.hpp"
#include "deck/deck_node.hpp"
#include "deck/deck_reader.hpp"

namespace ballista {

namespace {

class MaxRadiusProbe : public BodyAxisProbe {
 public:
  MaxRadiusProbe(int body, int axis, double plane, double distance, const Vec3& center)
      : BodyAxisProbe(body, axis), plane_(plane), distance_(distance), center_(center) {}

  double value(const ProbeContext& c) const override {
    const PointDomains domains(c.points, c.nd());
    double rmax = -std::numeric_limits<double>::infinity();
    for_each_point(c.points, [&](Index p) {
      if (std::abs(domains.x[p][axis()] - plane_) > distance_) return;
      domains.for_each_corner(p, [&](const Vec3& y) {
        rmax = std::max(rmax, distance_from_axis(y, center_, axis(), domains.nd));
      });
    });
    return max_over_ranks(rmax, c.comm);
  }

 private:
  double plane_, distance_;
  Vec3 center_;
};

/// The axis must cross the grid box: off-axis coordinates of the centre inside it (a centre at
/// 1e308 would give a foot radius of 1e308 or inf).
void check_center(const ProbeSpec& spec, const Scenario& sc) {
  const int axis = probe_axis(spec);
  const Vec3& center = spec.vectors.at("center");
  const int nd = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  for (int d = 0; d < nd; ++d)
    if (d != axis && !(center[d] >= sc.grid.lower[d] && center[d] <= sc.grid.upper[d]))
      throw ParamError("center", std::string("the probe's axis must pass through the grid box: ") + axis_name(d) +
                                     " = " + format_number(center[d]) + " m is outside [" +
                                     format_number(sc.grid.lower[d]) + ", " + format_number(sc.grid.upper[d]) + "] m");
}

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "max_radius",
    .description = "largest distance from the axis (through `center`, along `axis`) of the deformed domains of "
                   "particles whose centre is within `distance` of the plane at `plane` [m]",
    .unit = "m",
    .params = {body_param(),
               axis_param("axis of symmetry"),
               {.name = "plane", .kind = ProbeParam::Kind::Number, .unit = "m",
                .description = "position of the plane normal to `axis`", .required = false},
               {.name = "distance", .kind = ProbeParam::Kind::Number, .unit = "m",
                .description = "only particles within this distance of the plane", .min = 0.0, .min_exclusive = true},
               axis_point_param("a point on the axis of symmetry, inside the grid box")},
    .check = check_center,
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<MaxRadiusProbe>(probe_body(spec, sc), probe_axis(spec), spec.params.at("plane"),
                                              spec.params.at("distance"), spec.vectors.at("center"));
    }})

}  // namespace ballista
