#pragma once
// Solids of revolution given by their outline: a closed polygon in the half plane (r, a) of a
// radius r >= 0 from the axis and a distance a along it. The shapes `cone` (a frustum), `liner` (a
// conical shell: a shaped charge's liner, by apex angle, wall thickness and mouth diameter) and
// `revolution` (any outline: an explosive fill, a case) are all this one solid; in axisymmetric
// decks the outline is the body's section, in 3D it is swept about the axis, in plane strain it is
// the axial section (r = |distance from the axis line|).
#include <array>
#include <optional>
#include <string>
#include <vector>

namespace ballista {

/// A vertex (r, a) of an outline.
using OutlinePoint = std::array<double, 2>;
using Outline = std::vector<OutlinePoint>;

/// The frustum between radius `base` at a = 0 and `top` at a = length (either may be 0: a cone).
Outline cone_outline(double base, double top, double length);

/// A conical liner whose outer surface is the cone of full apex angle `angle_deg` with its apex at
/// a = 0, opening towards +a to the outer mouth diameter `diameter`; the wall is `thickness` thick
/// normal to it. With half-angle alpha and R = diameter / 2: the outer cone r = a tan(alpha) up to
/// the mouth plane a = H = R / tan(alpha), the inner one r = (a - t / sin(alpha)) tan(alpha), which
/// meets the mouth plane at R - t / cos(alpha) (> 0 required: t < R cos(alpha)).
Outline liner_outline(double angle_deg, double thickness, double diameter);

/// Why `o` is not a usable outline (fewer than 3 vertices, a negative radius, two edges that cross
/// or touch other than at their shared vertex, no area), or nothing if it is.
std::optional<std::string> outline_problem(const Outline& o);

/// Signed distance of (r, a) to the outline's boundary: > 0 inside, < 0 outside.
double outline_depth(const Outline& o, double r, double a);

/// Largest radius and the axial range of the outline.
void outline_extent(const Outline& o, double& r_max, double& a_min, double& a_max);

/// Volume of the solid of revolution (Pappus: 2 pi times the first moment of the outline's area
/// about the axis), m^3; the area of the outline, m^2, with `area`.
double outline_volume(const Outline& o, double* area = nullptr);

}  // namespace ballista
