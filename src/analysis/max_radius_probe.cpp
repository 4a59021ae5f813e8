// Probe `max_radius`: the largest distance from a symmetry axis of the deformed domains of the
// particles near a plane normal to it, m (e.g. the mushroomed radius of a rod's head).
#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/axis_distance.hpp"
#include "analysis/domain_corners.hpp"
#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "deck/deck_node.hpp"
#include "deck/deck_reader.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

class MaxRadiusProbe : public Probe {
 public:
  MaxRadiusProbe(int body, int axis, double plane, double distance, const Vec3& center)
      : body_(body), axis_(axis), plane_(plane), distance_(distance), center_(center) {}

  double value(const ProbeContext& c) const override {
    const int nd = c.dim == Dimension::ThreeD ? 3 : 2;
    const Index n = c.points.size();
    const auto* bid = c.points.ints(kBodyIndex);
    const auto* x = c.points.view(kPosition);
    const auto* F = c.points.view(kDeformationGradient);
    const auto* half = c.points.view(kHalfSize);
    const double kInf = std::numeric_limits<double>::infinity();
    double rmax = -kInf;
    for (Index p = 0; p < n; ++p) {
      if ((body_ >= 0 && bid[p] != body_) || std::abs(x[p][axis_] - plane_) > distance_) continue;
      for_each_corner(x[p], F[p], half[p], nd, [&](const Vec3& y) {
        rmax = std::max(rmax, distance_from_axis(y, center_, axis_, nd));
      });
    }
    rmax = c.comm.max(rmax);
    return rmax > -kInf ? rmax : std::nan("");
  }

 private:
  int body_;  // deck order, -1 = every body
  int axis_;
  double plane_, distance_;
  Vec3 center_;
};

/// The axis must cross the grid box: off-axis coordinates of the centre inside it (a centre at
/// 1e308 would give a foot radius of 1e308 or inf).
void check_center(const ProbeSpec& spec, const Scenario& sc) {
  const int axis = static_cast<int>(spec.params.at("axis"));
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
    .params = {{.name = "body", .kind = ProbeParam::Kind::Body, .unit = "",
                .description = "body measured (default: every body)"},
               {.name = "axis", .kind = ProbeParam::Kind::Axis, .unit = "", .description = "axis of symmetry"},
               {.name = "plane", .kind = ProbeParam::Kind::Number, .unit = "m",
                .description = "position of the plane normal to `axis`", .required = false},
               {.name = "distance", .kind = ProbeParam::Kind::Number, .unit = "m",
                .description = "only particles within this distance of the plane", .min = 0.0, .min_exclusive = true},
               {.name = "center", .kind = ProbeParam::Kind::Vector, .unit = "m",
                .description = "a point on the axis of symmetry, inside the grid box", .required = false}},
    .check = check_center,
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<MaxRadiusProbe>(probe_body(spec, sc), static_cast<int>(spec.params.at("axis")),
                                              spec.params.at("plane"), spec.params.at("distance"),
                                              spec.vectors.at("center"));
    }})

}  // namespace ballista
