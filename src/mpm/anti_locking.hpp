#pragma once
// Anti-locking for the MPM solver (deck key mpm.anti_locking): the cell-averaged F-bar of
// Coombs, Charlton, Cortis & Augarde, "Overcoming volumetric locking in material point methods",
// CMAME 333 (2018) 1-21 (incremental form), itself the F-bar of de Souza Neto, Peric, Dutko &
// Owen, IJSS 33 (1996) 3277 with the finite element replaced by the background-grid cell.
//
// MPM locks at nu -> 1/2 because every particle imposes its own volume constraint through its
// own dilatation; F-bar replaces each particle's volumetric increment by the average over the
// particles of its cell, leaving one constraint per cell:
//   dF_p    = I + dt L_p                      (thesis seed 000 eq. 4.9: F_{n+1} = dF_p F_n)
//   dJ_p    = det dF_p
//   dJbar_c = sum_{p in c} V_p^n dJ_p / sum_{p in c} V_p^n = V_c^{n+1} / V_c^n
//   dFbar_p = (dJbar_c / dJ_p)^(1/m) dF_p      (m = 3 in 3D and axisymmetric,
//                                             m = 2 in plane strain: the in-plane block only, so
//                                             F_zz = 1 stays exact)
// and then, so that everything the material update reads is consistent with it,
//   F_{n+1} = dFbar_p F_n,  V_p^{n+1} = V_p^0 det F_{n+1},  Lbar_p = (dFbar_p - I) / dt
// (the adapter's strain increment is computed from L, and it recovers F_n = (I + dt L)^-1 F_{n+1}:
// both see dFbar). The isochoric part of each particle's motion is untouched; each cell's volume
// change is exactly that of the standard update (sum_p V_p^{n+1} over the cell is unchanged).
//
// The cell of a point is the grid cell containing its position at t_{n+1} (the one call site is
// after the position update); a point that crosses a cell face within the step is averaged with
// its new cell, an O(dt) difference that vanishes with the step. All materials in a cell are
// averaged together (one velocity field: the no-slip contact of this solver already shares the
// grid motion between bodies).
//
// Thread determinism: the per-cell sums are accumulated in point order by one thread (two
// additions per point); the per-point passes before and after are independent per point, so the
// result is bitwise the same on any thread count.
#include <string>
#include <vector>

#include "core/tensor.hpp"
#include "mpm/grid_geometry.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

enum class AntiLocking { None, FBar };

/// "none" | "fbar"; throws ballista::Error listing the valid names otherwise.
AntiLocking parse_anti_locking(const std::string& name);
/// All valid names, in enum order (deck choices).
std::vector<std::string> anti_locking_names();

/// The point fields the correction reads and rewrites (views of the solver's FieldStore).
struct FBarPoints {
  Index count = 0;
  const Vec3* x = nullptr;        ///< positions at t_{n+1}, m
  Mat3* L = nullptr;              ///< velocity gradient of the step, 1/s (rewritten: Lbar)
  Mat3* F = nullptr;              ///< F_{n+1} = (I + dt L) F_n (rewritten: Fbar_{n+1})
  double* volume = nullptr;       ///< V_0 det F_{n+1}, m^3 (per radian in axisymmetric runs; rewritten)
  const double* volume0 = nullptr;///< reference volume, m^3
};

/// Cell-averaged F-bar (Coombs et al. 2018). Keeps its scratch buffers between steps: after the
/// first step with a given point and cell count, apply() allocates nothing.
class CellFBar {
 public:
  /// Replaces each point's volumetric increment by its cell's (see the header comment). dt > 0;
  /// every dJ_p = det(I + dt L_p) must be positive (the solver checks J > 0 before).
  void apply(const GridGeometry& g, Dimension dimension, double dt, const FBarPoints& pts);

 private:
  std::vector<Index> cell_;      ///< cell of each point (node index of its lowest corner)
  std::vector<double> v_old_p_;  ///< V_p^n = V_p^{n+1} / dJ_p of each point, m^3
  std::vector<double> v_new_;    ///< per cell: sum of V^{n+1}, m^3
  std::vector<double> v_old_;    ///< per cell: sum of V^n, m^3
};

}  // namespace ballista
