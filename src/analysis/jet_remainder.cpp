#include "analysis/jet_remainder.hpp"

#include <algorithm>
#include <cstdint>

#include "core/point_fields.hpp"

namespace ballista {

JetRemainder measure_jet_remainder(const FieldStore& pts, int body, const std::vector<JetSegmentLine>& segments,
                                   int axis, double direction, double scale) {
  const std::size_t n = segments.size();
  std::vector<double> eroded(n, 0.0), intact_mass(n, 0.0), intact_momentum(n, 0.0);
  const auto* bid = pts.ints(kBodyIndex);
  const auto* sid = pts.ints(kSegment);
  const auto* v = pts.view(kVelocity);
  const auto* m = pts.real(kMass);
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != body) continue;
    const auto k =
        static_cast<std::size_t>(std::clamp<std::int64_t>(sid ? sid[p] : 0, 0, static_cast<std::int64_t>(n) - 1));
    const double forward = direction * v[p][axis];  // speed along the line of flight
    if (forward >= kIntactSpeedFraction * segments[k].speed) {
      intact_mass[k] += m[p];
      intact_momentum[k] += m[p] * forward;
    } else {
      eroded[k] += m[p] * scale;
    }
  }
  JetRemainder r;
  double total = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    total += segments[k].length;
    // A segment cannot lose more than its length (its seeded mass may exceed the nominal section's).
    if (segments[k].mass_per_length > 0)
      r.consumed_length += std::min(segments[k].length, eroded[k] / segments[k].mass_per_length);
    if (r.tip_segment < 0 && intact_mass[k] > 0) {
      r.tip_segment = static_cast<int>(k);
      r.tip_velocity = intact_momentum[k] / intact_mass[k];
    }
  }
  r.remaining_length = std::max(0.0, total - r.consumed_length);
  return r;
}

}  // namespace ballista
