#pragma once
// The most hydrostatic tension a solid can hold: the spinodal of the universal equation of state
// of solids (P. Vinet, J.R. Smith, J. Ferrante, J.H. Rose, "Temperature effects on the universal
// equation of state of solids", Phys. Rev. B 35 (1987) 1945, eq. 4.1; J.H. Rose, J.R. Smith,
// F. Guinea, J. Ferrante, Phys. Rev. B 29 (1984) 2963 for the binding curve it integrates):
//   P(x) = 3 K0 (1 - x) / x^2 exp(eta (1 - x)),   x = (V/V0)^(1/3),   eta = 3 (K0' - 1) / 2.
// In tension (x > 1) P falls to a minimum and rises again towards zero as the atoms part: the
// minimum is the cohesive limit, where dP/dx = 0, i.e. eta x^2 + (1 - eta) x - 2 = 0. Copper
// (K0 = 139 GPa, K0' = 4.96) gives -19.6 GPa at V/V0 = 1.44; measured spall strengths are far
// smaller (defects open first), so a point below this limit holds a tension no solid of its
// moduli can, whatever its microstructure.
//
// A Mie-Grüneisen EOS with a linear Us-up line continues its tension branch linearly,
// p = rho0 c0^2 eta (eos.hpp), without such a minimum: a failed point that keeps its stress can be
// pulled apart at any tension. The line's K0' is 4 s - 1 (A.L. Ruoff, J. Appl. Phys. 38 (1967)
// 4976: the pressure derivative of the bulk modulus at zero pressure of a linear Us-up
// Hugoniot).
#include "materials/eos.hpp"

namespace ballista {

/// The universal EOS's cohesive limit (Pa, negative) of a solid with bulk modulus k0 (Pa) and
/// pressure derivative k0p (1, > 1).
double vinet_cohesive_limit(double k0, double k0p);

/// The volume ratio V/V0 at which that limit is reached (1).
double vinet_cohesive_volume_ratio(double k0p);

/// The cohesive limit of a Mie-Grüneisen EOS's solid (K0 = rho0 c0^2, K0' = 4 s - 1), Pa; -inf for
/// a linear EOS (no K0' to build one from) or a line with s <= 1/2 (K0' <= 1: no minimum).
double mie_gruneisen_cohesive_limit(const Eos& e);

}  // namespace ballista
