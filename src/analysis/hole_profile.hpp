#pragma once
// The wall of a hole or tunnel around the line of flight: what a gun designer reads as the
// casing's hole diameter and the tunnel's diameter in the rock (API RP 19B measures both). The
// innermost material is not the wall: crushed debris left lying in the tunnel, or a few points
// thrown back into the hole, would make it look closed. So the wall is where the material is
// dense: within each axial bin, the radial profile of the solid volume fraction (the points'
// current volumes, each spread over its own lateral extent so that annuli finer than the
// points' spacing see no gaps, over the volume of each annulus) is scanned outward from the axis; the
// first annulus whose fraction reaches one half and stays there over the next one too holds the
// wall, placed where the fraction, linear between the centres of that annulus and the one
// inside it, crosses one half. Loose debris fills an annulus far less than a half; an intact wall fills
// it entirely (tests/unit/analysis/test_hole_profile.cpp).
#include <vector>

namespace ballista {

/// How the lateral distance of a point measures an annulus: the r of an axisymmetric run
/// (volumes per radian), the radius about the line of flight in 3D, or |x| in plane strain
/// (both sides, volumes per unit thickness).
enum class LateralGeometry { Axisymmetric, ThreeD, PlaneStrain };

/// One point of a layer: its position along the line of flight (m, any origin), its distance
/// from the line (m) and its current volume (m^3, per radian or per unit thickness as the run).
struct LateralPoint {
  double axial = 0.0;
  double lateral = 0.0;
  double volume = 0.0;
  double half_width = 0.0;  ///< m: the point's lateral half-extent; its volume spreads evenly over it
};

struct WallOptions {
  double dr = 0.0;           ///< annulus width, m (the finest lateral cell)
  double threshold = 0.5;    ///< volume fraction that counts as wall
  int sustain = 2;           ///< consecutive annuli at or above it
};

/// The wall radius (m) of each of `bins` equal axial bins over [axial_lo, axial_hi]: in the first
/// annulus from the axis whose volume fraction and the next sustain - 1 ones' reach the threshold,
/// where the fraction interpolated from the inner annulus's centre crosses it (0 when the first
/// annulus is already wall); NaN where the points never make a wall.
std::vector<double> wall_radii(const std::vector<LateralPoint>& points, double axial_lo, double axial_hi, int bins,
                               LateralGeometry geometry, const WallOptions& options);

}  // namespace ballista
