// Surface pressure p(t) on a named surface of a body (a box's faces; a sphere's, cylinder's or
// tube's outer, inner, top and bottom), applied as point tractions on the current surface.
#include <algorithm>
#include <cstdint>

#include "core/error.hpp"
#include "core/names.hpp"
#include "geometry/seeding.hpp"
#include "points/load_registry.hpp"

namespace ballista {

namespace {

class Pressure final : public Load {
 public:
  Pressure(const LoadSpec& load, int k)
      : pressure_(load.params.at("pressure")), curve_(load.curve), area_field_("load_area_" + std::to_string(k)) {}

  /// Traction -p n da on the current surface, n da = J F^-T N dA0 (Nanson's formula). It acts at
  /// the point's face on the surface, x_p + F (N o half), not at its centre: a force at the centre
  /// puts part of the load on the node inside the boundary cell, whose stress then equilibrates
  /// only (1 - w) of the traction (a quarter short with two particles per cell, the surface-layer
  /// error of thesis seed 000 §5.1's particle point loads).
  void add_forces(const FieldStore& points, double time, LoadForces& out) override {
    const Index n = points.size();
    const auto* F = points.view<Mat3>("F");
    const auto* x = points.view<Vec3>("x");
    const auto* half = points.view<Vec3>("half_size");
    const auto* area = points.view<Vec3>(area_field_);
    const double pr = curve_.at(time) * pressure_;
    if (out.traction.size() != static_cast<size_t>(n)) out.traction.assign(n, Vec3{});
    update_surface_points(points);
    for (const Index p : surface_points_) {
      const Vec3 f = (-pr) * (cofactor(F[p]) * area[p]);
      const double a = norm(area[p]);
      Vec3 offset;
      for (int i = 0; i < 3; ++i) offset[i] = area[p][i] / a * half[p][i];
      out.total[p] += f;
      out.traction[p] += f;
      out.surface_forces.push_back({x[p] + F[p] * offset, f, p});
    }
  }

 private:
  double pressure_;  ///< Pa, positive pushes into the body
  LoadCurve curve_;
  std::string area_field_;  ///< the marked reference area vectors N dA0, m^2
  /// The points with a loaded surface area, in index order, found once per layout of the points
  /// (FieldStore::layout_version) instead of a scan every step.
  std::vector<Index> surface_points_;
  std::uint64_t surface_layout_ = UINT64_MAX;

  void update_surface_points(const FieldStore& points) {
    if (surface_layout_ == points.layout_version()) return;
    surface_points_.clear();
    const auto* area = points.view<Vec3>(area_field_);
    for (Index p = 0; p < points.size(); ++p)
      if (area[p][0] != 0.0 || area[p][1] != 0.0 || area[p][2] != 0.0) surface_points_.push_back(p);
    surface_layout_ = points.layout_version();
  }
};

/// The surfaces a pressure may load on a body of this shape in this kind of run; none for the shapes
/// whose faces are not named (solids of revolution, surface and mesh solids).
std::vector<std::string> surfaces(const ShapeSpec& s, Dimension dim) {
  if (s.type != "box" && s.type != "sphere" && s.type != "cylinder" && s.type != "tube") return {};
  const bool two_d = dim != Dimension::ThreeD;
  if (s.type == "box")
    return two_d ? std::vector<std::string>{"x_min", "x_max", "y_min", "y_max"}
                 : std::vector<std::string>{"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
  if (s.type == "sphere") return {"outer"};
  std::vector<std::string> out{"outer"};
  if (s.type == "tube") out.push_back("inner");
  if (!(dim == Dimension::PlaneStrain && s.axis == 2)) {
    out.push_back("top");
    out.push_back("bottom");
  }
  return out;
}

LoadReading read_pressure(LoadEntry& e, LoadSpec load) {
  load.body = e.body(true);
  const Scenario& sc = e.scenario();
  const BodySpec& body = sc.bodies[static_cast<size_t>(body_index(sc, load.body))];
  // The surface's points are those within one lattice spacing of it (mark_pressure_surface).
  if (body.seeding == "elements")
    e.fail("body", "a pressure on body '" + load.body + "', seeded at its mesh's elements, is not supported: the "
                   "loaded points are found on a lattice (seed the body with seeding: lattice)");
  const auto valid = surfaces(body.shape, sc.simulation.dimension);
  if (valid.empty())
    e.fail("body", "a pressure needs a body whose faces are named (a box, sphere, cylinder or tube); body '" +
                       load.body + "' is a " + body.shape.type);
  const std::string surface = e.string("surface");
  if (std::find(valid.begin(), valid.end(), surface) == valid.end()) {
    std::string hint;
    if (const std::string best = closest_name(surface, valid); !best.empty()) hint = " (did you mean '" + best + "'?)";
    e.fail("surface", "expected one of: " + join_names(valid) + " (the surfaces of body '" + load.body + "', a " +
                          body.shape.type + "), got '" + surface + "'" + hint);
  }
  load.params.choices["surface"] = surface;
  load.params["pressure"] = e.number("pressure", NumberRange::any("Pa"));
  const double hole = e.number("hole_radius", 0.0, NumberRange::non_negative("m"));
  if (hole > 0.0 && surface != "top" && surface != "bottom")
    e.fail("hole_radius", "a hole is cut in a cylinder's or tube's top or bottom face, not in surface '" + surface + "'");
  load.params["hole_radius"] = hole;
  load.curve = e.curve();
  return {{load}, {}};
}

/// Marks the points on the loaded surface with their reference area vectors (geometry/seeding).
std::vector<std::string> mark_pressure(const LoadSpec& load, int k, const LoadMarkContext& where,
                                       FieldStore& points) {
  if (mark_pressure_surface(load, k, where.body, where.body_index, where.cell_size, where.dim, points) == 0)
    throw DeckError(load.mark.file, load.mark.line, load.mark.column, load.mark.key_path + ".surface",
                    "no particle of body '" + load.body + "' lies on surface '" + load.params.choice("surface") +
                        "'");
  return {"load_area_" + std::to_string(k)};
}

}  // namespace

BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "pressure",
    .description = "pressure `pressure` (Pa, positive pushes in) on a named `surface` of a body, times the load "
                   "curve; Nanson-mapped onto the current surface",
    .read = read_pressure,
    .mark = mark_pressure,
    .create = create_load<Pressure>})

}  // namespace ballista
