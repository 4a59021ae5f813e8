#pragma once
// Reference response of a linear Drucker-Prager surface with an elliptical cap (Arenisca form,
// thesis seed 000 §4.1.1.3-4.1.1.4, eq. 4.2-4.6, Fig. 4.3) in compressive uniaxial strain, with the
// cap fixed or moving with the crush curve: CATALOGUE A8 (thesis Fig. 4.10a, b).
//
// The surface, written independently of the model (materials/geomodel_surface.hpp) from the thesis:
//   q = sqrt(J2) <= g(I1, X) = Ff(I1) Fc(I1, X),  Ff = FSLOPE (PEAKI1 - I1),
//   Fc = sqrt(1 - u^2), u = (kappa - I1)/(kappa - X) for I1 < kappa, else 1,
//   kappa - X = CR Ff(kappa), i.e. kappa = (X + CR FSLOPE PEAKI1)/(1 + CR FSLOPE);
// the cap X(evp) of the crush curve (hydrostatic_crush.hpp, eq. 4.5-4.6), or X = P0 if fixed.
// Associative flow, constant K and G, tension positive, I1 = tr(sigma).
//
// Reduction to an ODE. With e = -ln F11 (F = diag(F11, 1, 1)), D = diag(-1, 0, 0) de, and every
// deviator is a multiple of E1 = diag(2, -1, -1)/sqrt6: compression gives s = -sqrt2 q E1. The
// elastic response is I1 = -3K e, q = (2G/sqrt3) e. On the surface the plastic multiplier follows
// from consistency, dq = g_I dI1 + g_X X' devp, with the flow direction M = s/(2q) - g_I I
// (d eps^p = dlambda M, devp = -3 g_I dlambda) and the elastic law dI1 = 3K (-de - devp),
// dq = G (s:de_dev/q - dlambda) = G (2/sqrt3 de - dlambda):
//   dlambda/de = (2G/sqrt3 + 3K g_I) / (G + 9K g_I^2 - 3 g_X X' g_I),
//   devp/de = -3 g_I dlambda/de,   dI1/de = -3K (1 + devp/de),   q = g(I1, X(evp)).
// For a fixed cap (X' = 0) dI1/de = 3KG (2 sqrt3 g_I - 1)/(G + 9K g_I^2): constant on the flat
// cone, and zero where the cap's slope is g_I = 1/(2 sqrt3) (the strain rate parallel to the
// normal: all further strain is plastic), the state the stress approaches on a fixed cap.
// The ODE is integrated by fourth-order Runge-Kutta on a fine uniform grid in e from the yield
// point (found by bisection); the answer at any e is a cubic Hermite interpolant on that grid. Where
// the path enters the cap (I1 = kappa) the rate's derivative jumps, so the error there is third
// order in the grid step: 2e5 steps differ from 1e5 by 1.1e-9 of the stress scale and from 4e5 by
// 3e-10 (tests/unit/verify/test_exact_a7_a8.cpp), far below the 1e-4 step errors A8 measures.
#include <vector>

#include "verify/hydrostatic_crush.hpp"

namespace ballista {

struct CapSurfaceParams {
  double bulk = 0.0, shear = 0.0;  ///< K, G, Pa
  double peak_i1 = 0.0;            ///< PEAKI1, Pa
  double fslope = 0.0;             ///< FSLOPE
  double cap_ratio = 0.0;          ///< CR
  CrushCurve curve;                ///< X(evp); X(0) = P0
  bool fixed_cap = false;          ///< X = P0 throughout
};

/// The surface g(I1, X) and its partial derivatives.
struct CapSurfaceValue {
  double g = 0.0, g_i1 = 0.0, g_x = 0.0;
};
CapSurfaceValue cap_surface(const CapSurfaceParams& p, double i1, double X);

/// Uniaxial-strain response, from the stress-free state, on e in [0, e_max].
class UniaxialStrainCap {
 public:
  UniaxialStrainCap(const CapSurfaceParams& p, double e_max, int grid_steps = 200000);

  double yield_strain() const { return e_yield_; }
  /// I1, q = sqrt(J2) and evp at compressive log strain e (0 <= e <= e_max).
  double i1(double e) const;
  double q(double e) const;
  double evp(double e) const;
  /// X at e.
  double cap(double e) const;
  /// Fixed cap only: the stationary I1 on the cap, where g_I = 1/(2 sqrt3).
  double stationary_i1() const;

 private:
  double interpolate(const std::vector<double>& y, const std::vector<double>& dy, double e) const;
  double cap_of(double evp) const;
  double cap_slope(double evp) const;  ///< dX/devp
  CapSurfaceParams p_;
  double e_yield_ = 0.0, h_ = 0.0;
  std::vector<double> i1_, evp_, di1_, devp_;  ///< values and rates on the grid e_yield + k h
};

}  // namespace ballista
