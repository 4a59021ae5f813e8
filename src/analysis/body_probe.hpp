#pragma once
// What the probes that measure one body (or every body) share: the choice of the body's points, the
// deck parameters that name the body and an axis, and the reductions over the ranks that give NaN
// when no point qualifies. Each kind keeps only its own measurement.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>

#include "core/point_fields.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

/// A probe over the points of one body or of every body; it owns the body selection that every
/// such kind applies.
class BodyProbe : public Probe {
 public:
  explicit BodyProbe(int body) : body_(body) {}

 protected:
  /// Calls f(p) for each point of the measured body, in point order (sums stay in that order).
  template <class Fn>
  void for_each_point(const FieldStore& points, Fn&& f) const {
    const Index n = points.size();
    const std::int64_t* bid = points.ints(kBodyIndex);
    for (Index p = 0; p < n; ++p)
      if (body_ < 0 || bid[p] == body_) f(p);
  }

 private:
  int body_;  // deck order, -1 = every body
};

/// A body probe that measures along or about one axis (extent, max_radius, mean and radial
/// velocity).
class BodyAxisProbe : public BodyProbe {
 public:
  BodyAxisProbe(int body, int axis) : BodyProbe(body), axis_(axis) {}

 protected:
  int axis() const { return axis_; }

 private:
  int axis_;  // 0 x, 1 y, 2 z
};

/// The optional `body` parameter each body probe declares first, spelled once so that all read alike.
inline ProbeParam body_param() {
  return {.name = "body",
          .kind = ProbeParam::Kind::Body,
          .unit = "",
          .description = "body measured (default: every body)"};
}

/// An `axis` parameter (x, y or z) with what the axis means for the kind.
inline ProbeParam axis_param(std::string description) {
  return {.name = "axis", .kind = ProbeParam::Kind::Axis, .unit = "", .description = std::move(description)};
}

/// The optional `center` parameter of a kind measured about an axis: a point the axis passes through.
inline ProbeParam axis_point_param(std::string description) {
  return {.name = "center",
          .kind = ProbeParam::Kind::Vector,
          .unit = "m",
          .description = std::move(description),
          .required = false};
}

/// The `axis` a probe spec read, as 0, 1 or 2.
inline int probe_axis(const ProbeSpec& spec) { return static_cast<int>(spec.params.at("axis")); }

/// The largest of every rank's `local` maximum; NaN when no rank had a point (all still -inf).
inline double max_over_ranks(double local, const Communicator& comm) {
  const double m = comm.max(local);
  return m > -std::numeric_limits<double>::infinity() ? m : std::nan("");
}

/// sum[0] / sum[1] once both are summed over the ranks (a mass-weighted mean: sum m q / sum m);
/// NaN when no mass was selected.
inline double mass_weighted_mean(double sum[2], const Communicator& comm) {
  comm.sum(sum, 2);
  return sum[1] > 0.0 ? sum[0] / sum[1] : std::nan("");
}

/// The factory of a kind whose only deck parameters are a body and an axis (its constructor takes
/// both), written once for every such kind.
template <class P>
ProbeFactory body_axis_probe_factory(std::string name, std::string description, std::string unit,
                                     std::string axis_meaning) {
  return {.name = std::move(name),
          .description = std::move(description),
          .unit = std::move(unit),
          .params = {body_param(), axis_param(std::move(axis_meaning))},
          .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
            return std::make_unique<P>(probe_body(spec, sc), probe_axis(spec));
          }};
}

}  // namespace ballista
