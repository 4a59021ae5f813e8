#pragma once
// CATALOGUE A2, uniaxial strain with J2 plasticity (thesis seed 000 §4.1.1.2, Fig. 4.4-4.6;
// Uintah test 11), and its hardening variants (thesis Fig. 4.6 b, c), through the single-element
// driver, compared with the exact solution of uniaxial_strain_j2.hpp.
#include <cmath>
#include <string>
#include <vector>

#include "materials/material.hpp"
#include "verify/uniaxial_strain_j2.hpp"
#include "verify/verify_case.hpp"

namespace ballista {

enum class A2Hardening { None, Isotropic, Kinematic };

struct A2Problem {
  double bulk = 79e9;                   ///< K, Pa (catalogue)
  double shear = 70e9;                  ///< G, Pa (catalogue)
  double tau_y = 165e6;                 ///< yield in shear sqrt(J2), Pa (catalogue)
  double density = 7800.0;              ///< kg/m^3 (any: no inertia)
  /// Plastic modulus of the hardening variants. 20 GPa makes the Fig. 4.6 trends plain: the first
  /// plastic leg (Delta ln F11 = 4.08e-3) gives eps_p = 2G/(3G + H) x 4.08e-3 = 2.49e-3, i.e. a
  /// radius growth (isotropic) or backstress (kinematic) of H eps_p = 50 MPa, 17 % of sigma_y0.
  double hardening = 20e9;
  /// The catalogue's F11 table (t, F11), piecewise linear in t.
  std::vector<double> t{0, 1, 3, 5, 7, 8};
  std::vector<double> F11{1, 1.002043428, 1.006142645, 1.002043256, 0.997960739, 1};
  int substeps = 1000;                  ///< driver steps per table row
  int plot_every = 10;                  ///< plotted series keep every n-th step (and row ends)

  double yield() const { return std::sqrt(3.0) * tau_y; }  ///< sigma_y0 = sqrt(3) tau_y
  J2UniaxialParams params(A2Hardening h) const {
    return {bulk, shear, yield(), h == A2Hardening::Isotropic ? hardening : 0.0,
            h == A2Hardening::Kinematic ? hardening : 0.0};
  }
};

/// Runs A2 ("A2", "A2-iso", "A2-kin") on the model's reduce_j2 parameters; not applicable without
/// the hook or when it returns no parameters for the requested hardening kind.
VerifyCase run_a2(const MaterialFactory& f, A2Hardening h, const A2Problem& problem = {});

/// Elastic range on the first load reversal of a uniaxial-strain history (the trends of thesis
/// Fig. 4.6): found from the stress-strain data alone. q = sigma11 - sigma22.
struct ReversalYield {
  bool found = false;
  double q_max = 0.0;    ///< q at the reversal (on the yield surface after plastic loading)
  double q_yield = 0.0;  ///< q at the first plastic step after the reversal
  double e_yield = 0.0;  ///< ln F11 there
  double radius() const { return 0.5 * (q_max - q_yield); }  ///< elastic range / 2
  double centre() const { return 0.5 * (q_max + q_yield); }  ///< backstress
};
/// Scans e, q from the largest e onwards for the first step that leaves the elastic line
/// q = q_max - 2G (e_max - e) by more than `threshold` (Pa).
ReversalYield find_reversal_yield(const std::vector<double>& e, const std::vector<double>& q, double shear,
                                  double threshold);

}  // namespace ballista
