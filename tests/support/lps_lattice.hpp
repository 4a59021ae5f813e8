#pragma once
// Sums over the family of an interior point of the cubic lattice at horizon m = 3 spacings, with
// the solver's partial volumes (peridynamics/bond_family.hpp), by direct enumeration: the weighted
// volume of the linear peridynamic solid and its two shear quadratures (tests/unit/peridynamics/
// test_lps.cpp derives them; tests/verification/test_pd_lps.cpp uses them for the bar speed).
#include <cmath>

#include "peridynamics/bond_family.hpp"

namespace ballista::test {

struct LpsLatticeSums {
  double m = 0.0;      ///< sum |xi|^2 beta V, in units of dx^5
  double q44 = 0.0;    ///< 15 sum |xi|^2 n_x^2 n_y^2 beta V / m: shear eps_xy over G
  double qprime = 0.0; ///< (15/4) sum |xi|^2 (n_x^2 - n_y^2)^2 beta V / m: shear (eps_xx - eps_yy)/2 over G
};

inline LpsLatticeSums lps_lattice_sums() {
  double m = 0.0, txy = 0.0, tp = 0.0;
  for (int i = -4; i <= 4; ++i)
    for (int j = -4; j <= 4; ++j)
      for (int k = -4; k <= 4; ++k) {
        const double r2 = i * i + j * j + k * k, r = std::sqrt(r2);
        if (r2 == 0.0 || r > 3.0 * (1 + 1e-9)) continue;
        const double b = pd::partial_volume_factor(r, 3.0, 1.0);
        m += r2 * b;
        txy += r2 * (i * i / r2) * (j * j / r2) * b;
        tp += r2 * std::pow((i * i - j * j) / r2, 2) * b;
      }
  return {m, 15.0 * txy / m, 3.75 * tp / m};
}

}  // namespace ballista::test
