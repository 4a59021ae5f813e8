#pragma once
// The distortion limit of F for models whose stress does not read F's isochoric part.
//
// A hypoelastic-plastic model (J2, Johnson-Cook, the geomodel) or a fluid (water, explosive
// products) keeps its stress and history as state; of F it reads J = det F (volume, EOS) and the
// rotation R of F = R U (the unrotated frame, thesis seed 000 §2.3). Material that flows like a
// fluid (a jet's copper turning at the stagnation point, rock extruded along a crater wall) keeps
// stretching, and a point's F reaches stretches of 10^7 that no particle can represent: det F is
// then lost to cancellation (entries ~1e7, J ~ 0.3) and the polar decomposition fails, so the
// stress turns NaN. Beyond a stretch that carries no information for these models F is replaced
// by J^(1/3) R_{n+1} (R_{n+1} the step's rotation, found while F is still well conditioned at the
// limit): J and the frame (hence the unrotated stress) are unchanged, the stretch history
// is dropped, as an Eulerian or ALE remap does (it carries stress and history variables, never F:
// Benson, Comput. Methods Appl. Mech. Eng. 99 (1992) 235, §4). Hyperelastic models (neo-Hookean)
// read all of F and are never remapped.
#include "core/lanes.hpp"
#include "core/tensor.hpp"

namespace ballista {

/// True if F's RMS isochoric stretch sqrt(tr(F^T F) / (3 J^(2/3))) exceeds `limit` (J = det F > 0),
/// compared as tr(C)^3 > 27 limit^6 J^2 (no cube root on the path every point takes).
inline bool beyond_distortion_limit(const Mat3& F, double J, double limit) {
  double trC = 0.0;
  for (double f : F.a) trC += f * f;
  const double l2 = limit * limit;
  return trC * trC * trC > 27.0 * l2 * l2 * l2 * J * J;
}

/// The same test for kLanes points (lanes.hpp), all bits set in the lanes beyond `limit`.
inline LaneMask beyond_distortion_limit(const Mat3L& F, Lane J, double limit) {
  Lane trC = splat(0.0);
  for (const Lane& f : F.a) trC += f * f;
  const double l2 = limit * limit;
  return trC * trC * trC > 27.0 * l2 * l2 * l2 * J * J;
}

/// F := J^(1/3) R (same J, same rotation, no isochoric stretch) if F is beyond `limit` (J = det F,
/// R its rotation); true if it was. Out of line
/// (distortion.cpp): inlined into the stress update's loop, the check would change the compiler's
/// choices there and so the round-off of the geomodel's update, which must stay bitwise.
bool remap_if_distorted(Mat3& F, double J, const Mat3& R, double limit);

}  // namespace ballista
