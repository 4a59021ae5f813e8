#pragma once
// A body that starts in a uniform stress (BodySpec::prestress: the overburden of a rock target,
// thesis seed 000 §5.1) instead of being loaded to it by a ramp and a damped stage. One material
// point is driven through its own model's update along a proportional, quasi-static path of
// principal stretches until its stress is the requested one; every point of the body then takes
// that point's stress, deformation gradient and internal state, and its position and volume
// follow the deformation (about the body's centre of mass; in axisymmetric runs about the axis).
// For a homogeneous body whose surfaces carry exactly these tractions this is the equilibrium a
// damped stage converges to, and its state is the one the model reaches on the way, not assumed.
#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Drives one point of `material` to the principal stresses `stress` (Pa, tension positive; x, y, z
/// or r, z, theta) and copies the result to the points [first, last) of `points`, moving them
/// with it. Throws std::runtime_error naming the material if its model cannot carry that stress
/// (beyond its strength, or not reached within the drive's iterations).
void apply_prestress(const Material& material, const Vec3& stress, Dimension dim, FieldStore& points, Index first,
                     Index last);

}  // namespace ballista
