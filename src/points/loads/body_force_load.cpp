// Body forces: a given acceleration field b on every point of a body, f = m b, scaled by the load
// curve; `gravity` is the same with b = g along a direction (EMU seed 001: g = 9.814 m/s^2, the
// default of `g`).
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "points/load_registry.hpp"

namespace ballista {

namespace {

class BodyForce final : public Load {
 public:
  BodyForce(const LoadSpec& load, const Scenario& sc)
      : acceleration_(load.vectors.at("acceleration")), curve_(load.curve), body_(body_index(sc, load.body)) {}

  void add_forces(const FieldStore& points, double time, LoadForces& out) override {
    const Index n = points.size();
    const auto* mass = points.real(kMass);
    const auto* bid = points.ints("body");
    const Vec3 acc = curve_.at(time) * acceleration_;
    for_each(0, n, [&](Index p) {
      if (body_ < 0 || bid[p] == body_) out.total[p] += mass[p] * acc;
    });
  }

 private:
  Vec3 acceleration_;  ///< m/s^2
  LoadCurve curve_;
  int body_;  ///< -1: every body
};

LoadReading read_body_force(LoadEntry& e, LoadSpec load) {
  load.body = e.body(false);
  load.vectors["acceleration"] = e.vector("acceleration");
  load.curve = e.curve();
  return {{load}, {}};
}

LoadReading read_gravity(LoadEntry& e, LoadSpec load) {
  load.type = "body_force";
  load.body = e.body(false);
  const double g = e.number("g", 9.814, NumberRange::non_negative("m/s^2"));
  const Vec3 dir = e.vector("direction");
  if (!(norm(dir) > 0.0)) e.fail("direction", "expected a non-zero vector (the direction of gravity)");
  load.vectors["acceleration"] = (g / norm(dir)) * dir;
  load.curve = e.curve();
  return {{load}, {}};
}

}  // namespace

BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "body_force",
    .description = "acceleration field `acceleration` (m/s^2) on a body or every body, f = m b, times the load curve",
    .read = read_body_force,
    .create = create_load<BodyForce>})
BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "gravity",
    .description = "a body_force of `g` (m/s^2, default 9.814) along `direction`",
    .read = read_gravity})

}  // namespace ballista
