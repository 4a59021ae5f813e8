#pragma once
// Program burn: the lighting time of every explosive point by Huygens' construction (seed 001,
// "EMU Detonation Model" and "Program Burn": detonation times computed before time stepping,
// propagating around obstacles). The detonation front moves at the detonation speed D through
// explosive only, so a point lights at
//   t_p = min over detonators d of ( t_d + (length of the shortest path from x_d to x_p through
//         explosive) / D ).
// The shortest paths are found by an any-angle Dijkstra search (Lazy Theta*, Nash, Koenig & Tovey,
// AAAI 2010) over the graph whose edges join explosive points closer than `radius` =
// radius_factor x spacing where the straight segment between them stays inside cells that hold
// explosive (line of sight: inert material and void are obstacles the front must go around). A
// point reached from a settled point inherits that point's parent (the detonator, or the last
// point where the path bent), as in Huygens' construction the wavelet of the parent reaches it
// first; the straight line from the parent is checked when the point is settled, and if it is
// cut the point takes its best settled neighbour instead.
//
// Error of the path metric. In open explosive the paths are straight lines from the detonators:
// t = t_d + |x - x_d| / D to round-off (a plain graph search would overestimate by the
// neighbourhood's anisotropy: 3.6 % in 3D with edges of 3.2 spacings, measured). Around an
// obstacle the path bends at lattice points next to it, and the lattice obstacle (the union of
// its points' cells) sticks out up to ~0.7 spacings beyond the true one: an error O(h / size of
// the obstacle) — 1.4 % behind a disk of radius 25 spacings, 2.2 % at 15, 1.2 % around a
// rectangle of 20 x 30 (tests/unit/points/test_program_burn.cpp).
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista {

struct Detonator {
  Vec3 x;             ///< m, where the detonation starts
  double time = 0.0;  ///< s, when
};

struct ProgramBurnOptions {
  double speed = 0.0;          ///< m/s, detonation speed D
  double spacing = 0.0;        ///< m, the points' lattice spacing
  double radius_factor = 3.2;  ///< graph edges up to this many spacings (metric error above)
  int dim = 3;                 ///< 3, or 2 (z ignored)
};

struct ProgramBurnResult {
  std::vector<double> time;  ///< s, lighting time per point; +inf for inert or unreachable points
  Index unreachable = 0;     ///< explosive points no detonation front reaches (cut off by inert/void)
};

/// Lighting times of points x[0..n) of which explosive[p] != 0 are explosive. Every detonator
/// lights the explosive points within the edge radius that it sees (line of sight); a detonator
/// with none in reach is an Error naming it. Deterministic (ties broken by point index).
ProgramBurnResult program_burn(const Vec3* x, const char* explosive, Index n, const std::vector<Detonator>& detonators,
                               const ProgramBurnOptions& opt);

}  // namespace ballista
