#pragma once
// The deck of the MPM benchmarks (mpm_block_impact_bench, checkpoint_bench): a 3D J2 steel block
// (E = 200 GPa, sigma_y = 350 MPa, H = 1 GPa) striking a rigid wall at 200 m/s, 8 particles per
// cell, MUSL, FLIP 0.99, sort every 20 steps, `particles` particles in a block of nx x 0.8 nx x
// nx cells of 1 mm. The box leaves four empty cells around the block in x and z and two above;
// with box_volume_ratio > 0 it is instead that many times the block's volume (the margin grown
// alike in x, z and above the block). `update` is mpm.update (musl unless a benchmark says).
#include <cmath>
#include <cstdio>
#include <string>

namespace ballista::bench {

inline std::string block_impact_deck(long particles, const std::string& shape, double box_volume_ratio = 0.0,
                                     const std::string& update = "musl") {
  const double cells = static_cast<double>(particles) / 8.0;
  const int nx = static_cast<int>(std::lround(std::cbrt(cells / 0.8)));
  const int ny = static_cast<int>(std::lround(0.8 * nx));
  const double h = 1.0e-3;
  const double lx = nx * h, ly = ny * h;
  double m = 4 * h, top = 2 * h;
  if (box_volume_ratio > 0.0) {
    const double s = std::cbrt(box_volume_ratio);
    m = std::ceil(0.5 * (s - 1.0) * lx / h) * h;
    top = std::ceil((s - 1.0) * ly / h) * h;
  }
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
simulation: {solver: mpm, dimension: 3d, end_time: 1.0, cfl: 0.3, on_particle_exit: delete}
materials:
  steel: {model: j2_plasticity, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.29,
          yield_stress: 350.0e6, hardening_modulus: 1.0e9}
mpm: {shape_function: %s, update: %s, flip: 0.99, sort_every: 20}
grid:
  lower: [0, 0, 0]
  upper: [%g, %g, %g]
  cell_size: %g
  boundary: {y_min: wall}
bodies:
  - name: block
    material: steel
    shape: {type: box, lower: [%g, %g, %g], upper: [%g, %g, %g]}
    particles_per_cell: 2
    velocity: [0, -200.0, 0]
)",
                shape.c_str(), update.c_str(), lx + 2 * m, ly + top, lx + 2 * m, h, m, 0.0, m, m + lx, ly, m + lx);
  return buf;
}

}  // namespace ballista::bench
