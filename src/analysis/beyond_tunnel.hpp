#pragma once
// Penetrator material lying beyond the end of the open tunnel. A penetrator point can only be
// deeper than the tunnel's floor by a few cells while it drives that floor (the point's domain
// and the shape functions' support overlap the rock's by up to 1.5 cells). Points far beyond it
// sit in intact rock that nothing has opened: in the axisymmetric MPM runs they are single points
// near the axis that the contact read as sliding (docs/validation.md, "The contact normal near
// the axis"), carrying a negligible share of the jet. The deepest penetrator point is then not a
// depth of penetration; the tunnel's end is (the depth API RP 19B's sectioned target reads).
#include <vector>

namespace ballista {

struct BeyondTunnel {
  int points = 0;          ///< penetrator points deeper than floor + margin
  double mass = 0.0;       ///< their mass (the points' own units)
  double mass_share = 0.0; ///< that over the penetrator's mass (0 with no penetrator)
  double deepest = 0.0;    ///< m: the deepest of them (0 if none)
  double deepest_within = -1e300;  ///< m: the deepest penetrator point not beyond (-1e300 if none)
};

/// Penetrator points (`depth`, m below the face, and `mass`) deeper than `floor` + `margin` (m).
BeyondTunnel beyond_tunnel(const std::vector<double>& depth, const std::vector<double>& mass, double floor,
                           double margin);

/// Cells beyond the tunnel's floor that still count as driving it: the penetrator point's own
/// half-extent plus the GIMP support (1.5 cells) with half a cell to spare.
inline constexpr double kBeyondTunnelCells = 2.0;

}  // namespace ballista
