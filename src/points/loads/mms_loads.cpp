// The manufactured body forces of CATALOGUE B1 (axis-aligned) and B2 (generalized vortex): the
// force per unit mass that makes the manufactured displacement an exact solution, evaluated at
// the point's reference position (points/mms_*.hpp give the solutions and their sources).
#include "core/parallel.hpp"
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
    const auto* mass = points.real("mass");
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

/// The kind of the manufactured body force of `Solution`: every solution is read and built alike.
template <class Solution>
LoadFactory manufactured_load(std::string name, std::string description) {
  return {.name = std::move(name),
          .description = std::move(description),
          .read = read_manufactured,
          .create = create_load<ManufacturedBodyForce<Solution>>};
}

}  // namespace

BALLISTA_REGISTER_LOAD(manufactured_load<mms::AxisAligned>(
    "mms_axis_aligned", "manufactured body force of CATALOGUE B1 (axis-aligned displacement) on a body"))
BALLISTA_REGISTER_LOAD(manufactured_load<mms::GeneralizedVortex>(
    "mms_generalized_vortex", "manufactured body force of CATALOGUE B2 (generalized vortex) on a body"))

}  // namespace ballista
