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
// its new cell, an O(dt) difference that vanishes with the step. Each material in a cell is
// averaged on its own: the constraint F-bar relaxes is one material's incompressibility, and a
// cell where a copper jet meets crushed porous rock must not hand the rock's compaction to the
// copper (nor the copper's stiffness to the rock). With one material this is Coombs et al.'s
// average; Σ_p V_p^{n+1} over each material of each cell is the standard update's.
//
// Patches (mpm.fbar_patch = k > 1): the average runs over fixed blocks of k cells per axis
// instead of single cells, the F-bar patch of de Souza Neto, Pires & Owen, IJNME 62 (2005) 353
// (the patch's volume change is the standard update's, as the cell's is for k = 1). What it is for:
// a point that is the only one of its material in its cell has nothing to be averaged with, and
// the grid's in-plane compression of a sheet thinner than a cell (jet copper thinned along a
// crater's wall while its hoop stretch grows) squeezes it towards its equation of state's limit; a
// patch of k^d cells holds its neighbours. A patch is keyed by its lowest cell. (On the
// perforation demo 2 x 2 patches do not keep the step: they hand the jet's hot tip its
// neighbours' expansion instead; docs/validation.md.)
//
// Thread determinism: the per-cell sums are accumulated in point order by one thread (two
// additions per point); the per-point passes before and after are independent per point, so the
// result is bitwise the same on any thread count.
#include <cstdint>
#include <functional>
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
  const std::int64_t* material = nullptr;  ///< material index of each point (null: all one material)
  int materials = 1;              ///< number of materials (the material indices are below it)
};

/// What the internal forces read of each point when the F-bar is on (views of the solver's fields).
struct FBarForcePoints {
  Index count = 0;
  const Vec3* x = nullptr;                 ///< positions where the forces are computed, m
  const double* volume = nullptr;          ///< current volume, m^3 (per radian in axisymmetric runs)
  const Mat3* stress = nullptr;            ///< Cauchy stress, Pa
  const double* viscous_pressure = nullptr;///< bulk viscosity q, Pa (null: none)
  const std::int64_t* material = nullptr;  ///< material index of each point (null: all one material)
  int materials = 1;
};

/// Sums the per-(cell, material) partial sums over the MPI ranks that share a cell: two arrays of
/// `materials` doubles per grid node (node-major), summed in place so that every sharer holds the
/// same totals (the solver's GridExchange). Empty on one rank.
using FBarSlotSum = std::function<void(double* a, double* b, int materials)>;

/// Cell-averaged F-bar (Coombs et al. 2018). Keeps its scratch buffers between steps: after the
/// first step with a given point and cell count, apply() allocates nothing.
class CellFBar {
 public:
  /// Cells per axis of an averaging patch (>= 1; 1 = each cell on its own, the default).
  void set_patch(int cells) { patch_ = cells < 1 ? 1 : cells; }

  /// Replaces each point's volumetric increment by its cell's (see the header comment). dt > 0;
  /// every dJ_p = det(I + dt L_p) must be positive (the solver checks J > 0 before).
  void apply(const GridGeometry& g, Dimension dimension, double dt, const FBarPoints& pts,
             const FBarSlotSum& across_ranks = {});

  /// The pressure the internal forces use at each point, with the F-bar on: the volume average
  /// P_bar = sum V_p (p_p + q_p) / sum V_p over the point's material in its cell (p = -tr sigma / 3,
  /// q the bulk viscosity). The forces then read s_p - P_bar I instead of sigma_p - q_p I: the
  /// mean-dilatation pairing (Nagtegaal, Parks & Rice, CMAME 4 (1974) 153; Hughes, IJNME 15 (1980)
  /// 1413, the B-bar that goes with an F-bar). Why: the materials book their work with the
  /// averaged rate, sum_p V_p p_p tr Lbar_c = P_bar V_c tr Lbar_c, and F-bar keeps V_c tr Lbar_c =
  /// sum_p V_p tr L_p; the grid's forces do the work sum_p V_p p_p tr L_p, which equals it only if
  /// every point of the group carries P_bar. Without the pairing a copper jet's energy audit drifts
  /// by 5 % of its energy (the perforation demo at 1 mm). Writes out[p] = P_bar + tr(sigma_p) / 3,
  /// what the forces take off sigma_p's diagonal (in place of q_p): sigma_p - out[p] I = s_p - P_bar I.
  void force_pressure(const GridGeometry& g, const FBarForcePoints& pts, std::vector<double>& out,
                      const FBarSlotSum& across_ranks = {});

 private:
  int patch_ = 1;                ///< cells per axis of an averaging patch
  std::vector<Index> cell_;      ///< (cell, material) slot of each point: cell node index × materials + material
  std::vector<double> v_old_p_;  ///< V_p^n = V_p^{n+1} / dJ_p of each point, m^3
  std::vector<double> v_new_;    ///< per (cell, material): sum of V^{n+1}, m^3
  std::vector<double> v_old_;    ///< per (cell, material): sum of V^n, m^3

  /// Sizes the per-slot sums for this grid and material count (kept between calls) and cell_ for
  /// n points; returns the material count the slots use (1 without material indices).
  int prepare(const GridGeometry& g, const std::int64_t* material, int materials, Index n);
  /// Zeroes the slots about to be summed: those of the points on one rank, every slot when the
  /// sums go across ranks (the exchange sends whole blocks of nodes).
  void clear_slots(Index n, bool across_ranks);
};

}  // namespace ballista
