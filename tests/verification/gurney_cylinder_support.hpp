#pragma once
// The Gurney cylinder in axisymmetric MPM, as tests/verification/test_gurney.cpp checks it against
// Gurney's formula and test_pd_gas.cpp uses it as the continuum reference of the peridynamic gas: a
// long TNT cylinder (radius 10 mm) in a strengthless steel case (J2, 1 MPa), an axial slice of
// 1 mm between symmetry faces (an infinitely long cylinder), lit on the axis, to 20 us.
#include <cmath>
#include <cstdio>
#include <string>

namespace ballista::gurney {

constexpr double kRhoC = 1630.0, kRhoM = 7850.0;  // kg/m^3: TNT (preset tnt) and the case steel

/// Outer radius of the case of mass M = mc C per unit length around the 10 mm charge, m.
inline double case_radius(double mc, double a = 10.0e-3) { return a * std::sqrt(1.0 + mc * kRhoC / kRhoM); }

/// The deck at cell size h (2 particles per cell).
inline std::string mpm_cylinder_deck(double mc, double h) {
  const double a = 10.0e-3, b = case_radius(mc, a);
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
simulation: {solver: mpm, dimension: axisymmetric, end_time: 20.0e-6, cfl: 0.3, on_particle_exit: delete}
materials:
  tnt: {preset: tnt}
  steel: {model: j2_plasticity, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.29, yield_stress: 1.0e6,
          hardening_modulus: 0.0}
mpm: {shape_function: gimp, update: musl, flip: 0.99}
grid: {lower: [0, 0], upper: [0.08, 1.0e-3], cell_size: %.9g,
       boundary: {x_min: symmetry, y_min: symmetry, y_max: symmetry}}
bodies:
  - {name: charge, material: tnt, shape: {type: box, lower: [0, 0], upper: [%.9g, 1.0e-3]}, particles_per_cell: 2}
  - {name: case, material: steel, shape: {type: box, lower: [%.9g, 0], upper: [%.9g, 1.0e-3]}, particles_per_cell: 2}
detonation: {points: [{position: [0, 0.5e-3], time: 0}]}
)",
                h, a, a, b);
  return buf;
}

}  // namespace ballista::gurney
