#pragma once
// Bond families of bond-based peridynamics (Silling 2000; Silling & Askari, Comput. Struct. 83
// (2005) 1526): every pair of points closer than the horizon delta in the reference configuration.
// Built once from the reference positions by cell binning (cells of size delta: O(N) pairs
// tested, never O(N^2)). Stored in compressed rows, each bond in the rows of both of its ends, so
// that the force loop writes only its own point (no atomics, results independent of the thread
// count); a bond is broken for both ends because the breaking criterion is symmetric.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/parallel.hpp"
#include "core/tensor.hpp"

namespace ballista::pd {

/// Partial-volume correction of a neighbour cut by the horizon sphere: the share of the
/// neighbour's cell inside the horizon, taken linear in the bond length across one lattice
/// spacing dx (the simple "partial volume" algorithm reviewed by Seleson, CMAME 282 (2014) 184;
/// the form LAMMPS PERI uses): 1 for |xi| <= delta - dx/2, (delta + dx/2 - |xi|)/dx beyond.
/// Bonds end at the horizon (|xi| <= delta), so the factor never falls below about 1/2.
double partial_volume_factor(double xi, double delta, double dx);

/// Moments of the family of an interior point of the lattice of spacing dx (cubic in 3D, square in
/// 2D with unit thickness), with the same horizon rule and partial volumes as build_bond_family:
/// m1 = sum_j |xi_j| beta_j V_j (the bulk modulus of the PMB bond is c m1/18 in 3D, from the energy
/// density W = 1/4 c eps^2 m1 of a dilatation eps, Silling & Askari 2005 eq. 21) and
/// m2 = sum_{xi_j . e > 0} |xi_j| (xi_j . e) beta_j V_j along a lattice axis e (the energy per unit
/// area of the bonds crossing a lattice plane at the critical stretch is G = c s0^2 m2 / 2, the
/// discrete form of Silling & Askari 2005 eq. 25). Continuum values: m1 = pi delta^4, m2 = pi delta^5/5.
struct LatticeMoments {
  double m1 = 0.0;  ///< m^4 (3D)
  double m2 = 0.0;  ///< m^5 (3D)
};
LatticeMoments lattice_moments(double delta, double dx, bool partial, int dim);

/// Calls f(x, r, b, V) for every bond of an interior point's family on the lattice of spacing dx
/// (cubic in 3D, square in 2D), with build_bond_family's tie rule at the horizon and its partial
/// volumes: x the bond's component along the first lattice axis, r its length, b its partial-volume
/// factor, V the lattice cell's volume. The sums over it are the interior family's moments
/// (lattice_moments; the state-based solid's, lps_constants.hpp).
template <class F>
void for_each_lattice_bond(double delta, double dx, bool partial, int dim, F&& f) {
  const int M = static_cast<int>(std::ceil(delta / dx)) + 1;
  const int kr = dim == 3 ? M : 0;
  const double V = dim == 3 ? dx * dx * dx : dx * dx;
  const double reach2 = delta * delta * (1.0 + 2e-9);  // the tie rule of build_bond_family
  for (int i = -M; i <= M; ++i)
    for (int j = -M; j <= M; ++j)
      for (int k = -kr; k <= kr; ++k) {
        const double x = i * dx, y = j * dx, z = k * dx;
        const double r2 = x * x + y * y + z * z;
        if (r2 == 0.0 || r2 > reach2) continue;
        const double r = std::sqrt(r2);
        f(x, r, partial_volume_factor(r, delta, partial ? dx : 0.0), V);
      }
}

/// Bond ends of an interior point's family on the cubic (dim 3) or square (dim 2) lattice with
/// horizon m spacings: the lattice offsets 0 < |xi| <= m, ties at the horizon included as
/// build_bond_family includes them (m = 3: 122 in 3D, 28 in 2D). Beyond m = 100 the continuum
/// count 4/3 pi m^3 (pi m^2 in 2D), within 1 % there, since counting would be slow.
double lattice_family_size(double m, int dim);

struct BondFamily {
  std::vector<Index> offset;         ///< row start of each point (size n + 1)
  std::vector<std::int32_t> other;   ///< the other end of each bond
  std::vector<double> length0;       ///< reference length |xi|, m
  std::vector<float> volume_factor;  ///< partial-volume correction (1 if off)
  std::vector<std::uint8_t> broken;  ///< 1 once the bond has failed (never heals)

  Index points() const { return static_cast<Index>(offset.size()) - 1; }
  Index bonds() const { return static_cast<Index>(other.size()); }  ///< each bond counted at both ends
  /// Bytes of bond storage per (one-ended) bond.
  static constexpr double kBytesPerBond = sizeof(std::int32_t) + sizeof(double) + sizeof(float) + 1;
};

/// A family with rows of count[p] bonds each (offsets set, arrays sized, no bond broken; the
/// caller fills other, length0 and volume_factor).
BondFamily family_with_rows(const std::vector<Index>& count);
/// The same into `f`, reusing its arrays' capacity.
void family_with_rows(const std::vector<Index>& count, BondFamily& f);

/// Families of the n reference positions x0 with horizon delta; `dx` is the lattice spacing used
/// by the partial-volume correction (0: no correction). With `body` given, only points of the same
/// body are bonded (bodies are separate objects that meet through contact). Neighbours within each
/// row are in increasing index order. `dim` is 2 or 3 (in 2D the z components are ignored). Points
/// with gas[p] != 0 (detonation products, peridynamics/gas_pass.hpp) get no bonds here.
BondFamily build_bond_family(const Vec3* x0, Index n, double delta, double dx, int dim,
                             const std::int64_t* body = nullptr, const std::uint8_t* gas = nullptr);

/// Several ranks: the family of `f` restricted to the points with keep[p] != 0
/// (renumbered in their order) and to the bonds with at least one end owned (owned[p] != 0), so a
/// rank's own points keep their whole rows and its ghost copies only their bonds to own points.
BondFamily restrict_family(const BondFamily& f, const std::vector<char>& keep, const std::vector<char>& owned);

/// The gas family: every pair within the horizon with at least one gas end, across bodies (a gas
/// point's row holds all its neighbours, a solid point's row only its gas neighbours). Same
/// horizon rule, partial volumes and row order as build_bond_family.
/// `scale` (per point, nullptr: all 1): a gas point seeded on a lattice `scale` times coarser than
/// dx (a body's point_spacing) has the horizon scale x delta. Two gas ends pair within the smaller
/// of their horizons, a gas point and a solid within the gas point's; the partial volume takes the
/// finer end's spacing (a solid's is dx).
BondFamily build_gas_family(const Vec3* x0, Index n, double delta, double dx, int dim, const std::uint8_t* gas,
                            const double* scale = nullptr);

}  // namespace ballista::pd
