#pragma once
// What is left of a jet (or rod) after it has gone through a layer: the length it has lost to
// erosion, the length still intact and the speed of its new tip, for comparison with the
// hydrodynamic erosion of a jet through a plate (thesis seed 000 ch. 3: a plate of thickness T
// consumes T (V - U) / U of jet, T sqrt(rho_t / rho_p) in the strengthless limit of eq. 3.1-3.2).
//
// A penetrator point is intact while it still flies at >= kIntactSpeedFraction of its segment's
// initial speed along the line of flight. Hydrodynamically the eroded jet leaves the stagnation
// point backwards at 2U - V while the intact jet keeps V; the stagnation point itself moves at
// U = V / (1 + sqrt(rho_t / rho_p)), at most 0.69 V for copper into the densities of casing,
// cement and rock (>= 1900 kg/m^3), so the threshold separates the two with a margin.
// The eroded length of a segment is its eroded mass over its mass per unit length.
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"

namespace ballista {

struct JetSegmentLine {
  double speed = 0.0;            ///< initial speed along the line of flight, m/s
  double mass_per_length = 0.0;  ///< kg/m, of the modelled section (per radian x 2 pi in axisymmetry)
  double length = 0.0;           ///< m
};

struct JetRemainder {
  double consumed_length = 0.0;   ///< m: eroded mass / mass per length, summed over the segments
  double remaining_length = 0.0;  ///< m: total length - consumed
  double tip_velocity = 0.0;      ///< m/s: mean speed of the foremost segment's intact points (0 if none)
  int tip_segment = -1;           ///< index of that segment (-1: nothing intact)
};

inline constexpr double kIntactSpeedFraction = 0.8;

/// The remainder of penetrator `body` in `points` (fields body, segment, v, mass). `axis` and
/// `direction` give the line of flight; `scale` turns per-point masses into the section's (2 pi in
/// axisymmetric runs). Points not yet inserted into the run are intact by construction.
JetRemainder measure_jet_remainder(const FieldStore& points, int body, const std::vector<JetSegmentLine>& segments,
                                   int axis, double direction, double scale);

}  // namespace ballista
