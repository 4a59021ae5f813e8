#pragma once
// The hot loop of bond-based peridynamics: every bond evaluated once, from its lower-index end,
// acting on both ends (half the work of a loop over each point's whole family, and Newton's third
// law exact). A plain function of raw pointers so that the compiler keeps them in registers (the
// same loop in a lambda over std::vectors reloads them every bond: 1.8x slower, measured).
#include <cstdint>

#include "core/parallel.hpp"

namespace ballista::pd {

struct BondPassArgs {
  // State and bonds (read; `broken` and `plastic_stretch` also written).
  const double* x;                 ///< positions, 3 per point, m
  const double* vol0;              ///< reference volumes, m^3
  const std::int64_t* material;    ///< material of each point
  const double* micromodulus;      ///< c per material pair (nmat x nmat), N/m^6
  int nmat;
  const double* s0;                ///< critical stretch of each point (previous step)
  const double* length0;           ///< |xi| per bond, m
  const double* inv_length0;       ///< 1/|xi| per bond, 1/m
  const float* beta;               ///< partial-volume factor per bond
  const std::int32_t* other;       ///< other end per bond
  const std::int32_t* mirror;      ///< the bond's position in the other end's row
  std::uint8_t* broken;            ///< per bond (both copies set together)
  const Index* offset;             ///< row starts
  const Index* upper;              ///< first bond of each row with a higher-index other end
  double* plastic_stretch;         ///< per bond; null: micro-elastic bonds
  double yield_stretch;
  double alpha;                    ///< s0 = s00 - alpha s_min
  bool contact;                    ///< broken bonds' ends repel when they meet
  bool bonded_contact;             ///< intact bonds compressed below 0.9 |xi| repel too
  double cs_over_c;                ///< contact stiffness c_s / c = 15 / delta, 1/m
  double range;                    ///< 1.35 dx, m
  const double* x_prev;            ///< positions at the step's start (energy of a breaking bond)
  // Per-point sums (each bond adds to both ends).
  double* f;                       ///< force, 3 per point, N
  double* energy;                  ///< bond strain energy, J
  double* dissipated;              ///< this evaluation's dissipation (breaking, plastic flow), J
  double* vol_broken;              ///< sum of beta V over broken bonds, m^3
  double* smax;                    ///< max of -alpha s over intact bonds
  double* e_contact;               ///< contact-spring energy, J
  double* k_contact;               ///< sum of c_s V_other over active contacts, N/m^4
  const double* surface_factor;    ///< per point, bonds scaled by the mean of their ends'; null: none
  bool lammps_break = false;       ///< a breaking bond still acts this step (LAMMPS PERI's order)
};

/// The bonds of points [p0, p1) with their higher-index ends. Writes go to both ends: the caller
/// runs ranges in parallel only where no two of them touch the same points (pd_solver.cpp blocks).
void bond_pass(const BondPassArgs& a, Index p0, Index p1);

}  // namespace ballista::pd
