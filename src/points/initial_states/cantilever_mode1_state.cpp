// CATALOGUE B4: a box is a beam clamped at its x_min face, started in its first bending mode
// (thesis seed 000 §6.1.1 after Mast et al.; points/cantilever_mode.hpp): the body's velocity (its y
// component) becomes the tip speed of the mode shape.
#include "points/cantilever_mode.hpp"
#include "points/initial_state_registry.hpp"

namespace ballista {

namespace {

std::optional<BodyIssue> check_cantilever(const BodySpec& body) {
  if (body.shape.type != "box")
    return BodyIssue{"initial_state", "cantilever_mode1 needs a box body (the beam along x, clamped at its x_min "
                                      "face); body '" + body.name + "' is a " + body.shape.type};
  if (body.velocity[0] != 0.0 || body.velocity[2] != 0.0 || body.radial_speed != 0.0)
    return BodyIssue{"velocity",
                     "with initial_state cantilever_mode1 the velocity is the tip speed along y: [0, v, 0]"};
  return std::nullopt;
}

void apply_cantilever(const BodySpec& body, const Material&, FieldStore& points, Index first, Index last) {
  beam::CantileverMode1 mode;
  mode.root = body.shape.lower[0];
  mode.length = body.shape.upper[0] - body.shape.lower[0];
  mode.mid = 0.5 * (body.shape.lower[1] + body.shape.upper[1]);
  mode.tip_speed = body.velocity[1];
  const auto* x0 = points.view<Vec3>("x0");
  auto* v = points.view<Vec3>("v");
  for (Index p = first; p < last; ++p) v[p] = mode.velocity(x0[p]);
}

}  // namespace

BALLISTA_REGISTER_INITIAL_STATE(InitialStateFactory{
    .name = "cantilever_mode1",
    .description = "a box beam clamped at x_min in its first bending mode, tip speed = the body's y velocity "
                   "(CATALOGUE B4)",
    .check = check_cantilever,
    .apply = apply_cantilever})

}  // namespace ballista
