#pragma once
// Single-element driver: one material point driven by prescribed deformation (thesis seed 000
// §4.1.1 and §4.2.1; verification CATALOGUE §A). It calls Material::update through the same
// MaterialBatch path as the solvers, with L = (F_{n+1} F_n^-1 - I)/dt (thesis eq. 4.10), so a
// history extracted from a run replays exactly.
//
// The point lives in a one-point FieldStore that declares the solvers' point fields
// (declare_point_fields: F, R, L, stress, volume0 = 1 m^3, internal_energy, plastic_work, ...)
// and the model's state fields; each step fills a MaterialBatch exactly as
// MpmSolver::update_stress does (F_old not stored, so the adapter recovers it from F_new and L;
// energy accumulators set; F_new writable, so an erosion model may reset it and the next step
// starts from the F it left). Programs:
//
//  * F-table (DriveProgram::table, CATALOGUE §A, thesis §4.2.1). Row k gives F_k at t_k and an
//    optional rotation angle theta_k about axis a_k. Each row interval (t_{k-1}, t_k] is split
//    into `substeps` equal steps; at tau = j/substeps in it
//        F(tau)  = F_{k-1} + tau (F_k - F_{k-1})                (linear in time)
//        Q(tau)  = Rot(a_k, tau theta_k) Q_{k-1}                (Euler-Rodrigues; Q_0 = I)
//        F_applied = Q(tau) F(tau)
//    so the rotation accumulates linearly over the row about that row's axis, composed onto the
//    rotation of the previous rows. The first row is the initial state (its angle must be 0); the
//    first step starts from F_applied = F_0 with the model's initial_stress(F_0). With
//    substeps = 1 and no angles, a table of a particle's F at every solver step replays that
//    particle's stress history (thesis §4.2.1, Fig. 4.14) up to round-off in L.
//    Note: sym(L) dt would be first order in a rotation increment (a rigid rotation dtheta per
//    step has sym(Q(dtheta) - I) = (cos dtheta - 1) in the plane of rotation); the adapter hands
//    the model the midpoint increment of Hughes & Winget 1980 instead
//    (materials/strain_increment.hpp), zero for a rigid rotation, so rotating tables need no
//    special step size (A1 at N steps: O(theta G/(M N)) left, from unrotating at t_{n+1}).
//
//  * Legs (DriveProgram::legs). Each leg of `duration` takes `steps` equal steps. Every symmetric
//    component (11, 22, 33, 23, 13, 12) is either
//      - strain-controlled: `value` is the increment of logarithmic strain over the leg, applied
//        at constant rate: each step applies the spatial, symmetric increment dE (value/steps in
//        that component) as a coaxial stretch F_{n+1} = exp(dE) F_n. While the principal axes of
//        the increments do not change (e.g. diagonal dE), the Hencky strain ln V then advances by
//        exactly dE per step; with shear components the increments are integrated in the current
//        configuration (ln V equals their sum only to second order). L = (exp(dE) - I)/dt per
//        eq. 4.10 is symmetric (no spin); the model sees the midpoint increment 2 tanh(dE/2)
//        per step for a diagonal dE (materials/strain_increment.hpp), dE + O(dE^3).
//      - stress-controlled: `value` is the spatial Cauchy stress component (Pa) to reach at the
//        end of the leg; it is driven linearly in time from its value at the start of the leg
//        (so a target equal to the current value, e.g. 0 for the lateral components of uniaxial
//        stress, holds it). The matching components of dE are solved at every step by Newton's
//        method with a forward-difference Jacobian from trial updates on a copy of the point (the
//        committed state is the converged trial: no extra update), with a backtracking line
//        search, until every held component is within DriveProgram::stress_tolerance of its
//        target relative to the stress scale of the step (see point_driver.cpp).
//    Components not given are strain-controlled with zero increment (held strain).
#include <array>
#include <string>
#include <vector>

#include "core/tensor.hpp"
#include "materials/material.hpp"

namespace ballista {

/// One row of an F-table: F at time t and, optionally, a superimposed rotation of angle_deg
/// degrees about `axis` that accumulates linearly over the row ending at t (thesis §4.2.1).
struct FTableRow {
  double t = 0.0;             ///< s
  Mat3 F = Mat3::identity();  ///< deformation gradient at t (before the superimposed rotation)
  double angle_deg = 0.0;     ///< rotation added over the row (t_prev, t], degrees
  Vec3 axis{0.0, 0.0, 1.0};   ///< rotation axis (normalised by the driver)
};

/// Symmetric component order of DriveLeg (and of the model tangent): 11, 22, 33, 23, 13, 12.
inline constexpr int kVoigtI[6] = {0, 1, 2, 1, 0, 0};
inline constexpr int kVoigtJ[6] = {0, 1, 2, 2, 2, 1};
/// "11", "22", "33", "23", "13", "12".
const char* voigt_name(int k);

/// One leg of a strain or mixed program. Each symmetric component, in the order
/// (11, 22, 33, 23, 13, 12), is either strain-controlled (value = increment of logarithmic strain
/// over the leg, applied at constant rate) or stress-controlled (value = spatial Cauchy stress to
/// reach at the end of the leg, Pa, approached linearly in time from its value at the start of the
/// leg; e.g. 0 for the lateral components of uniaxial stress holds them at 0).
struct DriveLeg {
  double duration = 0.0;  ///< s (> 0)
  int steps = 1;          ///< steps over the leg (>= 1)
  std::array<bool, 6> stress_controlled{};
  std::array<double, 6> value{};
};

/// A deformation program: an F-table (with `substeps` equal steps per row) or a list of legs.
struct DriveProgram {
  std::vector<FTableRow> table;
  int substeps = 1;
  std::vector<DriveLeg> legs;
  // Extensions (defaults keep the original behaviour):
  /// Record every n-th step (>= 1); the last step of every row or leg is always recorded.
  int record_every = 1;
  /// Stress control converges when every held component satisfies |sigma_ij - target_ij| <=
  /// max(stress_tolerance * max(|sigma_{n+1}|, |targets|), 1e-14 x the largest Jacobian entry)
  /// (Frobenius norm; the second term is the round-off floor of eq. 4.10 near zero stress; see
  /// point_driver.cpp for both numbers).
  double stress_tolerance = 1e-10;
  /// Newton iterations allowed per step before a PhysicsError.
  int max_iterations = 50;
};

/// The state of the point after one step.
struct DriveRecord {
  double t = 0.0;
  Mat3 F;                     ///< deformation gradient (with any superimposed rotation)
  Mat3 R;                     ///< rotation of F = R U
  Mat3 sigma;                 ///< spatial Cauchy stress, Pa
  Mat3 sigma_bar;             ///< unrotated Cauchy stress R^T sigma R, Pa
  std::vector<double> state;  ///< model state fields, in DriveResult::state_names order
  double plastic_work = 0.0;  ///< plastic dissipation over the step, J/m^3
  // Extensions:
  long step = 0;                    ///< step number (0 = initial state)
  double internal_energy = 0.0;     ///< accumulated stress work, J per m^3 of reference volume
  double plastic_work_total = 0.0;  ///< accumulated plastic dissipation, J per m^3 of reference volume
  int iterations = 0;               ///< Newton iterations of the step (0 without stress control;
                                    ///< -1 marks the step that raised a PhysicsError, see below)
};

struct DriveResult {
  std::vector<std::string> state_names;
  std::vector<DriveRecord> records;  ///< records[0] is the initial state at the first time
  long steps = 0;                    ///< steps taken
  int max_iterations = 0;            ///< most Newton iterations any step needed
};

/// Index of the record nearest time t (a table row's end is recorded exactly, so this finds it).
size_t record_nearest(const DriveResult& result, double t);

/// Drives one point of `material` through `program`. Throws Error on a bad program (no rows and
/// no legs, both, non-increasing times, det F <= 0 or non-finite entries in the table or in an
/// interpolated step, zero rotation axis with a non-zero angle, non-positive durations or steps),
/// naming the row, leg or step; and PhysicsError if the stress turns non-finite (naming the step,
/// time, F, stress and state) or stress control does not converge.
DriveResult drive_point(const Material& material, const DriveProgram& program);

/// The same, except that a PhysicsError does not propagate: its message goes to `error` and the
/// result holds every record up to the last good step (for `ballista drive`, which writes the
/// history up to a reproduced failure). Program errors (Error) still throw. `error` is cleared
/// on success.
DriveResult drive_point(const Material& material, const DriveProgram& program, std::string& error);

}  // namespace ballista
