#pragma once
// Single-element driver: one material point driven by prescribed deformation (thesis seed 000
// §4.1.1 and §4.2.1; verification CATALOGUE §A). It calls Material::update through the same
// MaterialBatch path as the solvers, with L = (F_{n+1} F_n^-1 - I)/dt (thesis eq. 4.10), so a
// history extracted from a run replays exactly.
//
// (Interface fixed first so that the verification suite can be written against it; the
// implementation is in point_driver.cpp.)
#include <array>
#include <string>
#include <vector>

#include "core/tensor.hpp"
#include "materials/material.hpp"

namespace ballista {

/// One row of an F-table: F at time t and, optionally, a superimposed rotation of angle_deg
/// degrees about `axis` that accumulates linearly over the row ending at t (thesis §4.2.1).
struct FTableRow {
  double t = 0.0;               ///< s
  Mat3 F = Mat3::identity();    ///< deformation gradient at t (before the superimposed rotation)
  double angle_deg = 0.0;       ///< rotation added over the row (t_prev, t], degrees
  Vec3 axis{0.0, 0.0, 1.0};     ///< rotation axis (normalised by the driver)
};

/// One leg of a strain or mixed program. Each symmetric component, in the order
/// (11, 22, 33, 23, 13, 12), is either strain-controlled (value = increment of logarithmic strain
/// over the leg, applied at constant rate) or stress-controlled (value = Cauchy stress to hold, Pa;
/// e.g. 0 for the lateral components of uniaxial stress).
struct DriveLeg {
  double duration = 0.0;                  ///< s
  int steps = 1;                          ///< steps over the leg
  std::array<bool, 6> stress_controlled{};
  std::array<double, 6> value{};
};

/// A deformation program: an F-table (with `substeps` equal steps per row) or a list of legs.
struct DriveProgram {
  std::vector<FTableRow> table;
  int substeps = 1;
  std::vector<DriveLeg> legs;
};

/// The state of the point after one step.
struct DriveRecord {
  double t = 0.0;
  Mat3 F;            ///< deformation gradient (with any superimposed rotation)
  Mat3 R;            ///< rotation of F = R U
  Mat3 sigma;        ///< spatial Cauchy stress, Pa
  Mat3 sigma_bar;    ///< unrotated Cauchy stress R^T sigma R, Pa
  std::vector<double> state;  ///< model state fields, in DriveResult::state_names order
  double plastic_work = 0.0;  ///< plastic dissipation over the step, J/m^3
};

struct DriveResult {
  std::vector<std::string> state_names;
  std::vector<DriveRecord> records;  ///< records[0] is the initial state at the first time
};

/// Drives one point of `material` through `program`. Throws ParamError/Error on a bad program
/// (non-increasing times, J <= 0 in the table) and PhysicsError if the stress turns non-finite.
DriveResult drive_point(const Material& material, const DriveProgram& program);

}  // namespace ballista
