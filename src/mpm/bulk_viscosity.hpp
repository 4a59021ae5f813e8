#pragma once
// Artificial bulk viscosity for shocks (von Neumann & Richtmyer, J. Appl. Phys. 21 (1950) 232;
// the linear term of Landshoff, LA-1930 (1955); in the form of Wilkins, J. Comput. Phys. 36
// (1980) 281, as LS-DYNA's and Uintah MPM's artificial viscosity use it).
//
// A shock is a jump the grid cannot resolve: without a dissipative pressure the particles behind
// it ring (an oscillation of the shocked state about its Rankine-Hugoniot value) and the peaks of
// that ringing over-compress single particles, which with a Mie-Grueneisen EOS stiffen without
// bound as J -> 1 - 1/s and collapse the stable time step (docs/validation.md, "Shock ringing").
// The viscous pressure spreads the jump over a few cells and turns the jump's energy into heat.
#include <cmath>
#include <vector>

#include "points/point_set.hpp"

namespace ballista {

/// Coefficients of the bulk viscosity (deck mpm.bulk_viscosity_linear / _quadratic). Zero: off.
struct BulkViscosity {
  double linear = 0.0;     ///< C_L, of the term linear in the compression rate (LS-DYNA 0.06, Uintah 0.2)
  double quadratic = 0.0;  ///< C_Q, of the quadratic term (LS-DYNA 1.5, Uintah 2.0)
  /// mpm.bulk_viscosity_sound_speed: reference. The linear term reads each point's sound speed at
  /// its reference EOS energy (Material::reference_wave_speeds) instead of its current one. A
  /// point's Mie-Grueneisen sound speed grows with the heat the viscosity itself puts in (the
  /// Gamma0 E term of eos_bulk_modulus), and with the current speed each compression of a hot point
  /// heats it faster than the last; cold shocked metal sees nearly the same coefficient either way
  /// (docs/validation.md, "The heat is the bulk viscosity's").
  bool reference_sound_speed = false;
  bool active() const { return linear > 0.0 || quadratic > 0.0; }
};

/// Viscous pressure q (Pa) of a point compressing at tr D < 0 (1/s): q = rho l |tr D| (C_L c +
/// C_Q l |tr D|), rho the current density, c the sound speed (c_linear: the one the linear term
/// reads, the current one unless reference_sound_speed), l the cell size (Wilkins 1980, eq. 8-9;
/// Uintah's ConstitutiveModel::artificialBulkViscosity). Zero in expansion.
inline double bulk_viscosity_pressure(const BulkViscosity& bv, double rho, double c_linear, double l, double trD) {
  if (!(trD < 0.0)) return 0.0;
  const double rate = -trD;
  return rho * l * rate * (bv.linear * c_linear + bv.quadratic * l * rate);
}

/// The signal speed (m/s) that takes the place of c in the Courant condition when q acts:
/// Q + sqrt(Q^2 + c^2) with Q = C_L c_linear + C_Q l |tr D| (LS-DYNA Theory Manual, "Time step
/// control", the element time step with bulk viscosity; c_linear as in bulk_viscosity_pressure,
/// c the point's current sound speed). Equals c in expansion.
inline double bulk_viscosity_signal_speed(const BulkViscosity& bv, double c, double l, double trD, double c_linear) {
  if (!(trD < 0.0)) return c;
  const double Q = bv.linear * c_linear + bv.quadratic * l * (-trD);
  return Q + std::sqrt(Q * Q + c * c);
}
inline double bulk_viscosity_signal_speed(const BulkViscosity& bv, double c, double l, double trD) {
  return bulk_viscosity_signal_speed(bv, c, l, trD, c);
}
/// A point's signal speed in the Courant condition: its sound speed c, or where its viscous
/// pressure q acts (and it has a sound speed: not failed to zero stress) the one above from its L.
inline double point_signal_speed(const BulkViscosity& bv, double q, double c, double l, const Mat3& L,
                                 double c_linear) {
  if (!(q > 0.0 && c > 0.0)) return c;
  return bulk_viscosity_signal_speed(bv, c, l, L(0, 0) + L(1, 1) + L(2, 2), c_linear);
}

/// The point field holding q (Pa): the forces use stress - q I (MpmSolver::particles_to_grid).
inline constexpr FieldKey<double> kBulkViscosity{"bulk_viscosity"};
inline constexpr const char* kBulkViscosityField = kBulkViscosity.name();

/// What one pass of apply_bulk_viscosity reports.
struct BulkViscosityPass {
  double work = 0.0;          ///< J (per radian in axisymmetric runs): the viscous heating of the pass
  double signal_speed = 0.0;  ///< m/s: max over the points of bulk_viscosity_signal_speed + |v|
  double signal_rate = 0.0;   ///< 1/s: max over the points of that speed over the point's cell length
};

/// One pass over the points after a stress update over dt (the whole step, or one of USAVG's
/// halves) from their velocity gradient L: books the work of the viscous pressure the forces used
/// as heat (into internal_energy, and into the EOS energy density of the models that keep one,
/// so the shocked state reaches the Hugoniot's pressure), then sets q from this L. The forces used
/// the q stored before the pass (usl and musl; USAVG's second half), or the q of this L
/// (`book_new`: USAVG's first half, whose q the step's forces use). `c` and `c_reference` are
/// scratch (one per point; the second used with bv.reference_sound_speed only).
/// l is `cell`, or on a graded grid each point's own cell length `cells[p]`. The points [begin,
/// end) only (end < 0: to the last), the rest of `c` left as it was.
BulkViscosityPass apply_bulk_viscosity(PointSet& pts, const BulkViscosity& bv, double cell, double dt, bool book_new,
                                       std::vector<double>& c, std::vector<double>& c_reference,
                                       const double* cells = nullptr, Index begin = 0, Index end = -1);

}  // namespace ballista
