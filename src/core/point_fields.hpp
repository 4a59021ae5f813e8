#pragma once
// Keys of the point fields every discretisation shares (MPM particles, peridynamic points, OTM
// material points, the single-element driver). declare_point_fields (geometry/seeding.cpp)
// declares them in this order, which is also the order points are packed in when they migrate
// and the checkpoint's layout: a new common field goes at the end there.
// Axisymmetric runs store mass, volumes and energies per radian of revolution.
// A field only one solver uses has its key in that solver's folder (e.g. otm/otm_adaptivity.hpp);
// material state fields with a fixed name have theirs beside the model (materials/failure.hpp).
#include <cstdint>

#include "core/field_key.hpp"
#include "core/tensor.hpp"

namespace ballista {

/// Point id, unique over all ranks (1)
inline constexpr FieldKey<std::int64_t> kId{"id"};
/// Index of the point's body in Scenario::bodies (1)
inline constexpr FieldKey<std::int64_t> kBodyIndex{"body"};
/// Index of the point's material in the solver's material list (1)
inline constexpr FieldKey<std::int64_t> kMaterialIndex{"material"};
/// Piece of a segmented rod or discrete jet, 0 for plain bodies (1)
inline constexpr FieldKey<std::int64_t> kSegment{"segment"};
/// Current position (m)
inline constexpr FieldKey<Vec3> kPosition{"x"};
/// Position in the reference configuration, where the point was seeded (m)
inline constexpr FieldKey<Vec3> kReferencePosition{"x0"};
/// Velocity (m/s)
inline constexpr FieldKey<Vec3> kVelocity{"v"};
/// Deformation gradient F = dx/dx0 (1)
inline constexpr FieldKey<Mat3> kDeformationGradient{"F"};
/// Rotation R of the polar decomposition F = R U (1)
inline constexpr FieldKey<Mat3> kRotation{"R"};
/// Velocity gradient L = dv/dx over the current step (1/s)
inline constexpr FieldKey<Mat3> kVelocityGradient{"L"};
/// Cauchy stress, tension positive (Pa)
inline constexpr FieldKey<Mat3> kStress{"stress"};
/// Mass (kg)
inline constexpr FieldKey<double> kMass{"mass"};
/// Volume in the reference configuration (m^3)
inline constexpr FieldKey<double> kReferenceVolume{"volume0"};
/// Current volume (m^3)
inline constexpr FieldKey<double> kVolume{"volume"};
/// Half-widths of the point's reference domain, half the seeding spacing per axis (m)
inline constexpr FieldKey<Vec3> kHalfSize{"half_size"};
/// Internal energy of the point (J)
inline constexpr FieldKey<double> kInternalEnergy{"internal_energy"};
/// Plastic work dissipated in the point so far (J)
inline constexpr FieldKey<double> kPlasticWork{"plastic_work"};

}  // namespace ballista
