#pragma once
// Keys of the point fields only the peridynamic solver declares (the common ones are in
// core/point_fields.hpp). PdSolver declares them after the common and material fields.
#include "core/field_key.hpp"
#include "core/tensor.hpp"
#include "materials/failure.hpp"

namespace ballista::pd {

/// Broken share of the point's bonds, by the volume of their other points, 0..1 (1). The same
/// field, `damage`, as a failure criterion's measure (materials/failure.hpp): one damage dataset.
inline constexpr FieldKey<double> kBondDamage = kDamage;
/// Acceleration of the last force evaluation, kept for the next half step (m/s^2); not output.
inline constexpr FieldKey<Vec3> kAccel{"pd_accel"};

}  // namespace ballista::pd
