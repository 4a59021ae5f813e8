#pragma once
// Detonation products as a peridynamic gas (seed 001, "Gases as Peridynamic Materials"; Demmie &
// Silling, JoMMS 2 (2007) 1921). A gas point i has no bonds of its own stiffness; its neighbours
// (any body, within the horizon) only measure how far its neighbourhood has spread:
//   X_i = rho0/rho = [ (1/V_i) sum_j beta_ij (r_ij/p_ij)^m dV_j ]^(-d/m),  V_i = sum_j beta_ij dV_j,
// r = |xi| the reference and p = |eta + xi| the current bond length, d the dimension (seed: d = 3,
// m = 1, as in EMU). The pressure P_i(X_i, E_i) comes from the shared material library (the
// explosive's JWL or ideal-gas products, materials/explosive.cpp), which also books the energy
// -P dV. The pair force is the derivative of the gas energy: with U_i(X_i), dU_i = -P_i dV_i
// (dV_i = dV0_i dX_i), dU_i/dp_ij = -G_i beta_ij dV_j r^m / p^(m+1), G_i = d P_i X_i^(1+m/d) dV0_i/V_i,
// so the bond i-j pushes its ends apart with
//   |f_ij| = (G_i beta dV_j [i gas] + G_j beta dV_i [j gas]) r^m / p^(m+1).
// With P_i = P_j, X_i = X_j and both ends gas this is the seed's pairwise force
// f = -(6P/(r V)) (r/p)^(m+1) X^(1+m/3) times dV_i dV_j (m = 1, d = 3); the form per end keeps
// the work of the forces equal to the products' -P dV when the two ends differ, and lets a solid
// neighbour (the case) feel the gas through the same bond: this is how the products push the
// case. Bonds (rather than contact) because the gas-case interface is then exactly the gas's own
// pressure with no penalty stiffness to choose; a gas bond never breaks and never pulls.
#include <cstdint>
#include <vector>

#include "core/tensor.hpp"
#include "peridynamics/bond_family.hpp"
#include "peridynamics/chunked_rows.hpp"

namespace ballista::pd {

/// m of the seed's density measure (EMU uses m = 1).
inline constexpr double kGasExponent = 1.0;
/// A bond is never counted shorter than this fraction of its reference length: two points that
/// meet (round-off, a fragment edge) give a large but finite force (a compression X = 1e-3 in 3D,
/// beyond any state of the products).
inline constexpr double kGasMinStretchRatio = 0.1;
/// The density measure is capped here: products expanded 10^4 times carry no pressure worth the
/// round-off of a measure near 0 (gas that escapes without bound stays finite).
inline constexpr double kGasMaxExpansion = 1.0e4;

/// X of a gas point changes by at most this factor in one step (either way). In dilute products a
/// neighbour passing close dominates the m = 1 measure and could compress a point several-fold in
/// one step, more than the products' trapezoidal energy update can take (materials/explosive.cpp
/// refuses a volume falling below 1/(1 + 1/omega) of the old in one step); such gas carries little
/// pressure, and the limited steps are counted (result value gas_rate_limited_steps).
inline constexpr double kGasMaxStepRatio = 2.0;

struct GasPassArgs {
  const Vec3* x;             ///< current positions, m
  const double* vol0;        ///< reference volumes dV0, m^3
  const BondFamily* family;  ///< build_gas_family
  const std::uint8_t* gas;   ///< 1 for gas points
  const double* family_volume;  ///< V_i = sum_j beta dV_j of gas points, m^3
  const double* g;           ///< G_i = d P_i X_i^(1+m/d) dV0_i / V_i of gas points, Pa (0: no push)
  int dim = 3;
  /// The family renewed in the current configuration (build_renewed_gas_family), per row entry:
  /// the other end's reference length and the weight of this row's point in the other end's
  /// measure (volume_factor holds the other end's weight in this row's). nullptr: the reference
  /// family, one length and one partial-volume factor per bond.
  const double* length_other = nullptr;
  const float* weight_other = nullptr;
};

/// X_i of gas point i at the current positions (1 in the reference configuration; 1 for a point
/// without neighbours, which has nothing to measure: the solver keeps such a point's last X).
double density_measure(const GasPassArgs& a, Index i);

/// Force on point p (gas or solid) from its gas bonds at the current positions, N.
Vec3 gas_force(const GasPassArgs& a, Index p);

/// sum_j beta dV_j / |xi| over the gas row of p, 1/m^2 (the stable step of a gas point, pd_solver.cpp).
double gas_inverse_length_sum(const GasPassArgs& a, Index p);

/// The gas family renewed in the current configuration x (peridynamics.gas_refamily_steps): every
/// pair of gas points within delta min(s_p, s_q), s = X^(1/d) (capped at 2.5), and every gas point
/// and solid within delta; skip[p] != 0 leaves gas point p out (vented). A quadrature of the current neighbourhood,
/// so each neighbour weighs by its current volume dV0 X (volume_factor: the other end's X; a solid
/// end 1). Each row entry holds its own end's reference length |y| X_p^(-1/d) (a solid end: |y|)
/// and, in length_other and weight_other, the other end's length and this end's weight, so that
/// density_measure gives every gas point its X back and gas_force stays equal and opposite.
struct RenewedGasFamily {
  BondFamily family;
  std::vector<double> length_other;
  std::vector<float> weight_other;
};
/// `scale` (nullptr: all 1): a gas point seeded `scale` times coarser than the lattice of delta
/// (build_gas_family) searches scale times farther: s = scale X^(1/d) (X^(1/d) capped at 2.5), and
/// solids within scale x delta.
RenewedGasFamily build_renewed_gas_family(const Vec3* x, Index n, const std::uint8_t* gas, const std::uint8_t* skip,
                                          const double* X, double delta, int dim, const double* scale = nullptr);

/// Storage a renewal reuses from the last one: the family's arrays (hundreds of MB at 10^6 points)
/// and the search's buffers. Allocated afresh, each renewal would zero newly mapped pages on one
/// thread (9 % of a 10^6-point run's time, measured with perf).
struct GasRenewalWorkspace {
  struct Binned {
    Vec3 x;
    double s;  ///< the horizon over delta
    Index id;
  };
  ChunkedRows rows;
  std::vector<double> s, root;
  std::vector<Binned> gas_pts, sorted;
  std::vector<Vec3> gas_x, solid_x;
  std::vector<Index> solid_ids, cursor;
};
/// The same family written into `out`, reusing the capacity of out's and ws's arrays.
void build_renewed_gas_family(const Vec3* x, Index n, const std::uint8_t* gas, const std::uint8_t* skip,
                              const double* X, double delta, int dim, RenewedGasFamily& out, GasRenewalWorkspace& ws,
                              const double* scale = nullptr);

}  // namespace ballista::pd
