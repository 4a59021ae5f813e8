// The manufactured solutions' states at t = 0 (CATALOGUE B1 and B2; points/mms_*.hpp give the
// solutions and their sources), so that a body starts exactly on the solution its body force
// (points/loads/mms_loads.cpp) keeps it on.
#include "core/point_fields.hpp"
#include "points/initial_state_registry.hpp"
#include "points/mms_axis_aligned.hpp"
#include "points/mms_generalized_vortex.hpp"

namespace ballista {

namespace {

/// CATALOGUE B1 at t = 0: the lattice is the reference configuration X; the body starts displaced
/// by u(X, 0), with its velocity, F and the stress of F.
void apply_axis_aligned(const BodySpec&, const Material& material, FieldStore& points, Index first, Index last) {
  const mms::AxisAligned mms;
  auto* x0 = points.view<Vec3>("x0");
  auto* v = points.view<Vec3>("v");
  auto* F = points.view<Mat3>("F");
  auto* R = points.view<Mat3>("R");
  auto* stress = points.view<Mat3>("stress");
  auto* vol = points.real(kVolume);
  const auto* vol0 = points.real(kReferenceVolume);
  auto* x = points.view<Vec3>("x");
  for (Index p = first; p < last; ++p) {
    x[p] = x0[p] + mms.displacement(x0[p], 0.0);
    v[p] = mms.velocity(x0[p], 0.0);
    F[p] = mms.F(x0[p], 0.0);
    R[p] = Mat3::identity();  // F is diagonal and positive: no rotation
    stress[p] = material.initial_stress(F[p]);
    vol[p] = vol0[p] * det(F[p]);
  }
}

/// CATALOGUE B2 at t = 0: undeformed (alpha = 0), spinning with v = R alpha_t(R, 0) e_theta.
void apply_vortex(const BodySpec&, const Material&, FieldStore& points, Index first, Index last) {
  const mms::GeneralizedVortex mms;
  const auto* x0 = points.view<Vec3>("x0");
  auto* v = points.view<Vec3>("v");
  for (Index p = first; p < last; ++p) v[p] = mms.velocity(x0[p], 0.0);
}

std::optional<BodyIssue> check_vortex(const BodySpec& body) {
  if (body.shape.type == "tube" && body.shape.axis == 2 && body.shape.center[0] == 0.0 && body.shape.center[1] == 0.0)
    return std::nullopt;
  return BodyIssue{"initial_state", "mms_generalized_vortex needs a tube about the z axis through the origin (the "
                                    "annulus 0.75 <= R <= 1.25 of CATALOGUE B2)"};
}

}  // namespace

BALLISTA_REGISTER_INITIAL_STATE(InitialStateFactory{
    .name = "mms_axis_aligned",
    .description = "CATALOGUE B1's manufactured displacement, velocity, F and stress at t = 0",
    .apply = apply_axis_aligned})
BALLISTA_REGISTER_INITIAL_STATE(InitialStateFactory{
    .name = "mms_generalized_vortex",
    .description = "CATALOGUE B2's spinning annulus at t = 0 (a tube about z through the origin)",
    .check = check_vortex,
    .apply = apply_vortex})

}  // namespace ballista
