#include "points/point_loads.hpp"

#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "points/mms_axis_aligned.hpp"
#include "points/mms_generalized_vortex.hpp"

namespace ballista {

void PointLoads::compute(const Scenario& sc, const FieldStore& points, double time) {
  const Index n = points.size();
  if (sc.loads.empty()) {  // no loads: no external-force array, no external work
    fext_.clear();
    ftrac_.clear();
    surface_forces_.clear();
    reactions_.clear();
    return;
  }
  fext_.assign(n, Vec3{});
  ftrac_.clear();
  surface_forces_.clear();
  reactions_.clear();
  const auto* mass = points.real(kMass);
  const auto* bid = points.ints(kBodyIndex);
  for (size_t k = 0; k < sc.loads.size(); ++k) {
    const LoadSpec& load = sc.loads[k];
    const double scale = load.curve.at(time);
    const int body = body_index(sc, load.body);  // -1: every body
    if (load.type == "body_force") {
      const Vec3 acc = scale * load.acceleration;
      for_each(0, n, [&](Index p) {
        if (body < 0 || bid[p] == body) fext_[p] += mass[p] * acc;
      });
    } else if (load.type == "pressure") {
      // Traction -p n da on the current surface, n da = J F^-T N dA0 (Nanson's formula). It acts
      // at the point's face on the surface, x_p + F (N o half), not at its centre: a force at
      // the centre puts part of the load on the node inside the boundary cell, whose stress then
      // equilibrates only (1 - w) of the traction (a quarter short with two particles per cell,
      // the surface-layer error of thesis seed 000 §5.1's particle point loads).
      const auto* F = points.view(kDeformationGradient);
      const auto* x = points.view(kPosition);
      const auto* half = points.view(kHalfSize);
      const auto* area = points.view<Vec3>("load_area_" + std::to_string(k));
      const double pr = scale * load.pressure;
      if (ftrac_.size() != static_cast<size_t>(n)) ftrac_.assign(n, Vec3{});
      update_surface_points(sc, points);
      for (const Index p : surface_points_[k]) {
        const Vec3 f = (-pr) * (cofactor(F[p]) * area[p]);
        const double a = norm(area[p]);
        Vec3 offset;
        for (int i = 0; i < 3; ++i) offset[i] = area[p][i] / a * half[p][i];
        fext_[p] += f;
        ftrac_[p] += f;
        surface_forces_.push_back({x[p] + F[p] * offset, f, p});
      }
    } else if (load.type == "indenter") {
      // LAMMPS fix indent (sphere and plane): F = K (R - r)^2 pushing the point out, with K a force
      // per unit volume here (F = k V0 d^2 for an overlap d), so the same k works at any lattice
      // spacing. The indenter moves rigidly: centre c0 + v t.
      const IndenterSpec& in = load.indenter;
      const Vec3 c = in.center + time * in.velocity;
      const auto* x = points.view(kPosition);
      const auto* vol0 = points.real(kReferenceVolume);
      // The force on point p (zero outside the indenter), evaluated in both passes below rather
      // than stored: no per-step array.
      auto force = [&](Index p) {
        if (body >= 0 && bid[p] != body) return Vec3{};
        if (in.shape == "sphere") {
          const Vec3 d = x[p] - c;
          const double r = norm(d);
          if (r < in.radius && r > 0.0) return (in.stiffness * vol0[p] * (in.radius - r) * (in.radius - r) / r) * d;
          return Vec3{};
        }
        const double h = dot(x[p] - c, in.normal);  // < 0: inside the wall
        return h < 0.0 ? (in.stiffness * vol0[p] * h * h) * in.normal : Vec3{};
      };
      double r[3];
      deterministic_sum<3>(0, n, [&](Index p, double* o) {
        const Vec3 f = force(p);
        for (int a = 0; a < 3; ++a) o[a] -= f[a];
      }, r);
      reactions_.push_back(Vec3{{r[0], r[1], r[2]}});
      for_each(0, n, [&](Index p) { fext_[p] += force(p); });
    } else if (load.type == "mms_axis_aligned") {
      const mms::AxisAligned mms;
      const auto* x0 = points.view(kReferencePosition);
      for_each(0, n, [&](Index p) {
        if (body < 0 || bid[p] == body) fext_[p] += mass[p] * mms.body_force(x0[p], time);
      });
    } else if (load.type == "mms_generalized_vortex") {
      const mms::GeneralizedVortex mms;
      const auto* x0 = points.view(kReferencePosition);
      for_each(0, n, [&](Index p) {
        if (body < 0 || bid[p] == body) fext_[p] += mass[p] * mms.body_force(x0[p], time);
      });
    }
  }
}

}  // namespace ballista

namespace ballista {

std::vector<std::string> PointLoads::history_columns(const Scenario& sc) {
  std::vector<std::string> c;
  for (const LoadSpec& l : sc.loads)
    if (l.type == "indenter")
      for (const char* a : {"_fx", "_fy", "_fz"}) c.push_back(l.indenter.name + a);
  return c;
}

std::vector<double> PointLoads::history_values(const Scenario& sc) const {
  std::vector<double> v;
  for (const Vec3& r : reactions_)
    for (int a = 0; a < 3; ++a) v.push_back(r[a]);
  v.resize(history_columns(sc).size(), 0.0);
  return v;
}

void PointLoads::update_surface_points(const Scenario& sc, const FieldStore& points) {
  if (surface_layout_ == points.layout_version() && surface_points_.size() == sc.loads.size()) return;
  surface_points_.assign(sc.loads.size(), {});
  const Index n = points.size();
  for (size_t k = 0; k < sc.loads.size(); ++k) {
    if (sc.loads[k].type != "pressure") continue;
    const auto* area = points.view<Vec3>("load_area_" + std::to_string(k));
    for (Index p = 0; p < n; ++p)
      if (area[p][0] != 0.0 || area[p][1] != 0.0 || area[p][2] != 0.0) surface_points_[k].push_back(p);
  }
  surface_layout_ = points.layout_version();
}

}  // namespace ballista
