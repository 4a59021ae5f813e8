// A rigid indenter pressed into the points (LAMMPS `fix indent`, sphere and plane): each point
// overlapping it by d > 0 is pushed out with F = K d^2, with K a force per unit volume here
// (F = k V0 d^2, V0 the point's reference volume) so that the same k works at any lattice
// spacing. The indenter moves rigidly at a constant velocity (centre c0 + v t) and feels the
// opposite force, its reaction: history columns <name>_fx, _fy, _fz (N).
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "points/load_registry.hpp"

namespace ballista {

namespace {

class Indenter final : public Load {
 public:
  Indenter(const LoadSpec& load, const Scenario& sc)
      : name_(load.params.choices.at("name")),
        sphere_(load.params.choices.at("shape") == "sphere"),
        center_(load.vectors.at("center")),
        radius_(sphere_ ? load.params.at("radius") : 0.0),
        normal_(sphere_ ? Vec3{} : load.vectors.at("normal")),
        velocity_(load.vectors.at("velocity")),
        stiffness_(load.params.at("stiffness")),
        body_(body_index(sc, load.body)) {}

  void add_forces(const FieldStore& points, double time, LoadForces& out) override {
    const Index n = points.size();
    const Vec3 c = center_ + time * velocity_;
    const auto* x = points.view<Vec3>("x");
    const auto* vol0 = points.real(kReferenceVolume);
    const auto* bid = points.ints("body");
    // The force on point p (zero outside the indenter), evaluated in both passes below rather
    // than stored: no per-step array.
    auto force = [&](Index p) {
      if (body_ >= 0 && bid[p] != body_) return Vec3{};
      if (sphere_) {
        const Vec3 d = x[p] - c;
        const double r = norm(d);
        if (r < radius_ && r > 0.0) return (stiffness_ * vol0[p] * (radius_ - r) * (radius_ - r) / r) * d;
        return Vec3{};
      }
      const double h = dot(x[p] - c, normal_);  // < 0: inside the wall
      return h < 0.0 ? (stiffness_ * vol0[p] * h * h) * normal_ : Vec3{};
    };
    double r[3];
    deterministic_sum<3>(0, n, [&](Index p, double* o) {
      const Vec3 f = force(p);
      for (int a = 0; a < 3; ++a) o[a] -= f[a];
    }, r);
    reaction_ = Vec3{{r[0], r[1], r[2]}};
    for_each(0, n, [&](Index p) { out.total[p] += force(p); });
  }

  std::vector<std::string> history_columns() const override {
    return {name_ + "_fx", name_ + "_fy", name_ + "_fz"};
  }
  /// The force of the points on the indenter, N, summed over this rank's points in a fixed order
  /// (zeros before the first step).
  std::vector<double> history_values() const override { return {reaction_[0], reaction_[1], reaction_[2]}; }

 private:
  std::string name_;
  bool sphere_;      ///< sphere, else plane
  Vec3 center_;      ///< sphere: centre at t = 0; plane: a point of the plane at t = 0, m
  double radius_;    ///< sphere radius, m
  Vec3 normal_;      ///< plane: unit normal pointing out of the indenter (into the free space)
  Vec3 velocity_;    ///< m/s
  double stiffness_; ///< k, N/m^5: force per unit point volume and squared overlap
  int body_;         ///< -1: every body
  Vec3 reaction_;    ///< N
};

LoadReading read_indenter(LoadEntry& e, LoadSpec load) {
  const Scenario& sc = e.scenario();
  load.body = e.body(false);
  const std::string name = e.string("name", "indenter" + std::to_string(sc.loads.size()));
  load.params.choices["name"] = name;
  const std::string shape = e.word("shape", {"sphere", "plane"});
  load.params.choices["shape"] = shape;
  if (shape == "sphere") {
    load.vectors["center"] = e.vector("center");
    load.params["radius"] = e.number("radius", NumberRange::positive("m"));
  } else {
    load.vectors["center"] = e.vector("point");
    const Vec3 nrm = e.vector("normal");
    if (!(norm(nrm) > 0.0)) e.fail("normal", "expected a non-zero vector (out of the indenter, into the space)");
    load.vectors["normal"] = (1.0 / norm(nrm)) * nrm;
  }
  load.vectors["velocity"] = e.vector("velocity", Vec3{});
  load.params["stiffness"] = e.number("stiffness", NumberRange::positive("N/m^5"));
  for (const LoadSpec& other : sc.loads)
    if (other.type == "indenter" && other.params.choice("name") == name)
      e.fail("name", "indenter name '" + name + "' is used twice (it names history columns)");
  return {{load}, {}};
}

}  // namespace

BALLISTA_REGISTER_LOAD(LoadFactory{
    .name = "indenter",
    .description = "rigid sphere or plane moving at `velocity` (m/s), pushing points out with k V0 d^2 (LAMMPS fix "
                   "indent); its reaction is a history column",
    .read = read_indenter,
    .create = create_load<Indenter>})

}  // namespace ballista
