#pragma once
// Anti-locking for the OTM solver (otm.anti_locking: fbar): an F-bar whose volumetric increment is
// averaged over the nodes' supports, the meshfree counterpart of the average nodal pressure
// tetrahedron of Bonet & Burton, Commun. Numer. Meth. Engng 14 (1998) 437 (element volume ratios
// averaged at the nodes with volume weights, interpolated back), in the incremental form of
// Coombs, Charlton, Cortis & Augarde, CMAME 333 (2018) 1, that MPM's cell-averaged F-bar uses
// (src/mpm/anti_locking.hpp). The seed names locking under isochoric flow among OTM's lessons
// (seed 003, ch. 6): every point imposes its own volume constraint; here each node's support
// shares one.
//   dF_p     = I + dt L_p,  dJ_p = det dF_p,  V_p^n = V_p^{n+1} / dJ_p
//   theta_a  = sum_p N_a(x_p) V_p^n dJ_p / sum_p N_a(x_p) V_p^n        (per node)
//   dJbar_p  = sum_a N_a(x_p) theta_a                                    (per point)
//   dFbar_p  = (dJbar_p / dJ_p)^(1/m) dF_p   (m = 3 in 3D and axisymmetric, hoop included; m = 2
//                                             in plane strain: the in-plane block, F_zz = 1 exact)
// then F_{n+1} = dFbar_p F_n, V_p^{n+1} = V_p^0 det F_{n+1} and Lbar_p = (dFbar_p - I) / dt, which
// the material update reads. The isochoric part of each point's motion is untouched, and by the
// partition of unity sum_p V_p^n dJbar_p = sum_p V_p^n dJ_p: the body's volume change is exactly
// the standard update's. N are the step's shape functions (at x_p^k, those that moved the points).
//
// Thread and rank determinism: the nodal sums are folds over each node's points in point order
// (otm/node_sums.hpp: bitwise the serial run's on any rank count); the passes before and after are
// independent per point.
#include <vector>

#include "core/tensor.hpp"
#include "otm/node_sums.hpp"
#include "otm/otm_support.hpp"

namespace ballista::otm {

/// The point fields the correction reads and rewrites.
struct FBarFields {
  Index count = 0;
  Mat3* L = nullptr;          ///< velocity gradient of the step, 1/s (rewritten: Lbar)
  Mat3* F = nullptr;          ///< F_{n+1} = (I + dt L) F_n (rewritten)
  double* volume = nullptr;   ///< V_0 det F_{n+1}, m^3 (rewritten)
  const double* volume0 = nullptr;
  Mat3* extent = nullptr;     ///< adaptivity's extent tensor, carried by dF (rewritten; may be null)
  Mat3* Fr = nullptr;         ///< adaptivity's F since the last re-generation (rewritten; may be null)
};

/// Node-averaged F-bar over one step (header comment). `plane`: plane strain (m = 2, in-plane block).
class NodalFBar {
 public:
  /// `nodes`: the solver's influence domains of `sup` (and its ranks); null: built here, one rank.
  void apply(const Supports& sup, Index node_count, bool plane, double dt, const FBarFields& f,
             const NodeFoldScope* nodes = nullptr);

 private:
  std::vector<double> dj_, vn_;        ///< per point: dJ_p, V_p^n
  std::vector<double> theta_;          ///< per node: theta_a
  Influences inf_;                     ///< sup seen from the nodes (when the caller has none)
};

}  // namespace ballista::otm
