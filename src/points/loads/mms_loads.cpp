// The manufactured body forces of CATALOGUE B1 (axis-aligned) and B2 (generalized vortex): the
// force per unit mass that makes the manufactured displacement an exact solution, evaluated at
// the point's reference position (points/mms_*.hpp give the solutions and their sources).
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "points/load_registry.hpp"
#include "points/mms_axis_aligned.hpp"
#include "points/mms_generalized_vortex.hpp"

namespace ballista {

namespace {

template <class Solution>
class ManufacturedBodyForce final : public Load {
 public:
  ManufacturedBodyForce(const LoadSpec& load, const Scenario& sc) : body_(body_index(sc, load.body)) {}

  void add_forces(const FieldStore& points, double time, LoadForces& out) override {
    const Index n = points.size();
    const auto* mass = points.real(kMass);
    const auto* bid = points.ints("body");
    const Solution mms;
    const auto* x0 = points.view<Vec3>("x0");
    for_each(0, n, [&](Index p) {
      if (body_ < 0 || bid[p] == body_) out.total[p] += mass[p] * mms.body_force(x0[p], time);
    });
  }

 private:
  int body_;
};

LoadReading read_manufactured(LoadEntry& e, LoadSpec load) {
  load.body = e.body(true);
  return {{load}, {}};
}

}  // namespace

BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "mms_axis_aligned",
    .description = "manufactured body force of CATALOGUE B1 (axis-aligned displacement) on a body",
    .read = read_manufactured,
    .create = create_load<ManufacturedBodyForce<mms::AxisAligned>>})
BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "mms_generalized_vortex",
    .description = "manufactured body force of CATALOGUE B2 (generalized vortex) on a body",
    .read = read_manufactured,
    .create = create_load<ManufacturedBodyForce<mms::GeneralizedVortex>>})

}  // namespace ballista
