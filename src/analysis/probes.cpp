#include "analysis/probes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/axis_distance.hpp"
#include "core/error.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Calls f(corner) for each corner of a point's deformed domain (4 in 2D, 8 in 3D).
template <class Fn>
void for_each_corner(const Vec3& x, const Mat3& F, const Vec3& half, int nd, Fn&& f) {
  const int ncorner = nd == 3 ? 8 : 4;
  for (int c = 0; c < ncorner; ++c) {
    const Vec3 s{{(c & 1 ? 1.0 : -1.0) * half[0], (c & 2 ? 1.0 : -1.0) * half[1],
                  nd == 3 ? (c & 4 ? 1.0 : -1.0) * half[2] : 0.0}};
    f(x + F * s);
  }
}

}  // namespace

void validate_probes(const std::vector<ProbeSpec>& probes, const FieldStore& points) {
  for (const auto& pr : probes) {
    if (pr.type != "field_max") continue;
    if (!points.has(pr.field) || points.info(pr.field).ncomp != 1 ||
        points.info(pr.field).type != FieldType::Real) {
      std::string names;
      for (const auto& fi : points.fields())
        if (fi.ncomp == 1 && fi.type == FieldType::Real) names += (names.empty() ? "" : ", ") + fi.name;
      throw DeckError(pr.mark.file, pr.mark.line, pr.mark.column, pr.mark.key_path + ".field",
                      "field_max needs a scalar field; '" + pr.field + "' is not one (scalar fields: " + names + ")");
    }
  }
}

double evaluate_probe(const ProbeSpec& pr, int body, const FieldStore& points,
                      const EnergyTotals& e, Dimension dim, const Communicator& comm) {
  if (pr.type == "energy") {
    if (pr.field == "kinetic") return e.kinetic;
    if (pr.field == "internal") return e.internal;
    if (pr.field == "plastic") return e.plastic;
    if (pr.field == "external") return e.external;
    return e.total();
  }
  const int nd = dim == Dimension::ThreeD ? 3 : 2;
  const Index n = points.size();
  const auto* bid = points.ints("body");
  const auto* x = points.view<Vec3>("x");
  const auto* F = points.view<Mat3>("F");
  const auto* half = points.view<Vec3>("half_size");
  auto selected = [&](Index p) { return body < 0 || bid[p] == body; };

  if (pr.type == "extent") {
    double lo = kInf, hi = -kInf;
    for (Index p = 0; p < n; ++p) {
      if (!selected(p)) continue;
      for_each_corner(x[p], F[p], half[p], nd, [&](const Vec3& y) {
        lo = std::min(lo, y[pr.axis]);
        hi = std::max(hi, y[pr.axis]);
      });
    }
    lo = comm.min(lo);
    hi = comm.max(hi);
    return hi >= lo ? hi - lo : std::nan("");
  }
  if (pr.type == "max_radius") {
    double rmax = -kInf;
    for (Index p = 0; p < n; ++p) {
      if (!selected(p) || std::abs(x[p][pr.axis] - pr.plane) > pr.distance) continue;
      for_each_corner(x[p], F[p], half[p], nd, [&](const Vec3& y) {
        rmax = std::max(rmax, distance_from_axis(y, pr.center, pr.axis, nd));
      });
    }
    rmax = comm.max(rmax);
    return rmax > -kInf ? rmax : std::nan("");
  }
  if (pr.type == "field_max") {
    const double* f = points.real(pr.field);
    double m = -kInf;
    for (Index p = 0; p < n; ++p)
      if (selected(p)) m = std::max(m, f[p]);
    m = comm.max(m);
    return m > -kInf ? m : std::nan("");
  }
  throw Error("unknown probe type '" + pr.type + "'");
}

}  // namespace ballista
