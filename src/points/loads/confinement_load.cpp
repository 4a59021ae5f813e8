// The overburden on a cylindrical rock target (thesis seed 000 §5.1, Table 5.1): pressure
// `radial` on its outer surface and `axial` on its top and bottom (both default to `pressure`;
// optionally none within `hole_radius` of the axis on the top, where the penetrator enters),
// read as three pressure loads with the same curve, and the stress they hold the target at in
// equilibrium, for stages that wait for it. With `prestress: true` the target starts in that
// stress (points/prestress.hpp) instead of being brought to it by a ramp and a damped stage: the
// uniform stress is the exact equilibrium of a solid cylinder under these tractions.
#include <fmt/format.h>

#include "points/load_registry.hpp"

namespace ballista {

namespace {

LoadReading read_confinement(LoadEntry& e, LoadSpec load) {
  load.body = e.body(true);
  const Scenario& sc = e.scenario();
  const BodySpec& body = sc.bodies[static_cast<size_t>(body_index(sc, load.body))];
  if (body.shape.type != "cylinder" || !body.segments.empty())
    e.fail("body", "a confinement acts on a cylinder (outer, top and bottom surfaces); body '" + load.body + "' is a " +
                       (body.segments.empty() ? body.shape.type : body.penetrator.kind));
  if (sc.simulation.dimension == Dimension::PlaneStrain && body.shape.axis == 2)
    e.fail("body", "a plane-strain disk has no top and bottom; use pressure loads");
  const double p = e.number("pressure", 0.0, NumberRange::non_negative("Pa"));
  const double radial = e.number("radial", p, NumberRange::non_negative("Pa"));
  const double axial = e.number("axial", p, NumberRange::non_negative("Pa"));
  // The penetrator enters through the top face; a hole there keeps loaded points out of its channel.
  const double hole = e.number("hole_radius", 0.0, NumberRange::non_negative("m"));
  if (hole >= body.shape.radius)
    e.fail("hole_radius", fmt::format("the hole ({:g} m) must be narrower than the cylinder's radius ({:g} m)", hole,
                                      body.shape.radius));
  load.curve = e.curve();
  LoadReading out;
  out.prestress = e.boolean("prestress", false);
  if (out.prestress && sc.simulation.dimension == Dimension::PlaneStrain)
    e.fail("prestress", "a prestress needs the stress along every axis; in plane strain the out-of-plane one is not "
                        "the load's (use 3d or axisymmetric)");
  if (out.prestress && load.curve.at(0.0) != 1.0)
    e.fail("curve", fmt::format("a prestressed target is held by the full load from t = 0; the curve gives {:g} "
                                "there (drop the ramp, or prestress: false)",
                                load.curve.at(0.0)));
  load.type = "pressure";
  for (const char* surface : {"outer", "top", "bottom"}) {
    load.params.choices["surface"] = surface;
    load.params["pressure"] = std::string(surface) == "outer" ? radial : axial;
    load.params["hole_radius"] = std::string(surface) == "top" ? hole : 0.0;
    out.loads.push_back(load);
  }
  Vec3 stress;
  for (int d = 0; d < 3; ++d) stress[d] = d == body.shape.axis ? -axial : -radial;
  if (sc.simulation.dimension == Dimension::Axisymmetric) stress = Vec3{{-radial, -axial, -radial}};
  out.equilibrium_stress = stress;
  return out;
}

}  // namespace

BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "confinement",
    .description = "overburden on a cylinder: `radial` on its outer surface, `axial` on top and bottom (Pa, both "
                   "default to `pressure`), as three pressure loads; `prestress: true` seeds the cylinder in that "
                   "stress",
    .read = read_confinement})

}  // namespace ballista
