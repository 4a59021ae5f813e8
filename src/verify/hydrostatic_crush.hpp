#pragma once
// Exact hydrostatic response of a drained linear Drucker-Prager + cap model with a crush curve:
// verification CATALOGUE A4 and A5 (thesis seed 000 §4.1.1.4, eq. 4.5-4.6, Fig. 4.10c-4.12;
// Arenisca3 crush curve as in the geomodel contract, notes4/geomodel_spec.md).
//
// Crush curve (contract; tension positive, evp = plastic volumetric strain):
//   evp <= 0 (compaction):  X = P0 + ln(1 + evp/P3)/P1
//   evp >  0 (dilatation):  X = P0 (1 + evp)^(1/(P0 P1 P3))
// Porosity: phi = 1 - exp(-(P3 + evp))  (thesis eq. 4.6), phi0 = 1 - exp(-P3). On the cap
// (I1 = X) this is thesis eq. 4.5: phi = 1 - exp(-P3 exp(P1 (I1 - P0))) for I1 < P0 and, from the
// dilatation branch, phi = 1 - exp(1 - (I1/P0)^(P0 P1 P3) - P3) for I1 >= P0 (the seed prints the
// exponent as a product, "P0 P1 P3 (I1/P0)": a transcription slip; the power is what the crush
// curve gives).
//
// Hydrostat. With F = lambda I the stress stays isotropic (sqrt(J2) = 0) and the only variables
// are I1 and evp. With constant K the total volumetric strain ev = 3 ln lambda splits as
//   ev = evp + I1/(3K)
// and the yield surface crosses the hydrostat at the cap X(evp) (compression) and at the vertex
// PEAKI1 (tension). So for any ev the state follows from the previous evp alone:
//   elastic      X(evp) <= 3K (ev - evp) <= PEAKI1: I1 = 3K (ev - evp)
//   compaction   trial below the cap: solve evp' + X(evp')/(3K) = ev (monotone in evp', a unique
//                root in (-P3, evp)); I1 = X(evp'). With a fixed cap: I1 = P0, evp' = ev - P0/(3K)
//   dilatation   trial above the vertex: I1 = PEAKI1, evp' = ev - PEAKI1/(3K)
// This is the exact solution of the rate problem whenever consecutive samples bracket every
// reversal of ev (within a monotone piece the rate equations integrate to the same map).
#include <vector>

namespace ballista {

/// The crush curve and the porosity it implies (see the header comment for the equations).
struct CrushCurve {
  double p0 = 0.0;  ///< P0, Pa (< 0): cap at evp = 0
  double p1 = 0.0;  ///< P1, 1/Pa (> 0)
  double p3 = 0.0;  ///< P3 = -ln(1 - phi0) (> 0)

  double cap(double evp) const;                 ///< X(evp), Pa
  double evp_at_cap(double x) const;            ///< inverse of cap(): evp with X(evp) = x
  double porosity(double evp) const;            ///< thesis eq. 4.6
  double porosity_at_cap(double i1) const;      ///< thesis eq. 4.5 (I1 on the cap)
  double initial_porosity() const;              ///< phi0 = 1 - exp(-P3)
};

enum class HydroPhase { Elastic, Compaction, Dilatation };

struct HydroCapParams {
  double bulk = 0.0;     ///< K, Pa (constant)
  double peak_i1 = 0.0;  ///< PEAKI1, Pa (> 0)
  CrushCurve curve;
  bool fixed_cap = false;  ///< cap frozen at P0 (no hardening)
};

/// Exact hydrostatic response (see the header comment).
class HydrostaticCap {
 public:
  explicit HydrostaticCap(const HydroCapParams& p);
  /// Moves the total volumetric strain to ev (the previous sample and ev must bracket no reversal).
  void advance_to(double ev);
  double ev() const { return ev_; }
  double i1() const { return i1_; }
  double evp() const { return evp_; }
  double cap() const;  ///< current X (P0 for a fixed cap)
  double porosity() const { return p_.curve.porosity(evp_); }
  HydroPhase phase() const { return phase_; }

 private:
  HydroCapParams p_;
  double ev_ = 0.0, i1_ = 0.0, evp_ = 0.0;
  HydroPhase phase_ = HydroPhase::Elastic;
};

/// Compaction root: the evp with evp + X(evp)/(3K) = ev, searched in (-P3, evp_hi] (bisection to
/// round-off; g is strictly increasing). Throws Error if ev lies above g(evp_hi) (no compaction).
double solve_compaction(const CrushCurve& c, double bulk, double ev, double evp_hi);

}  // namespace ballista
