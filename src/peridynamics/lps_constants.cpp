// The constants of the linear peridynamic solid (formulas and sources in lps_constants.hpp).
#include "peridynamics/lps_constants.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "peridynamics/bond_family.hpp"

namespace ballista::pd {

LpsMoments lps_moments(bool lattice, double delta, double dx, bool partial) {
  LpsMoments m;
  if (!lattice) {
    m.m = 4.0 * std::numbers::pi * std::pow(delta, 5) / 5.0;
    m.m3 = std::numbers::pi * std::pow(delta, 6) / 6.0;
    return m;
  }
  // The lattice family of build_bond_family (its tie rule and partial volumes), as lattice_moments.
  const int M = static_cast<int>(std::ceil(delta / dx)) + 1;
  const double V = dx * dx * dx;
  const double reach2 = delta * delta * (1.0 + 2e-9);
  for (int i = -M; i <= M; ++i)
    for (int j = -M; j <= M; ++j)
      for (int k = -M; k <= M; ++k) {
        const double x = i * dx, y = j * dx, z = k * dx;
        const double r2 = x * x + y * y + z * z;
        if (r2 == 0.0 || r2 > reach2) continue;
        const double b = partial_volume_factor(std::sqrt(r2), delta, partial ? dx : 0.0);
        m.m += r2 * b * V;
        if (x > 0.0) m.m3 += x * r2 * b * V;
      }
  return m;
}

double lps_critical_stretch(std::optional<double> given, std::optional<double> fracture_energy, double shear,
                            const LpsMoments& moments) {
  if (given) return *given;
  if (!fracture_energy) return std::numeric_limits<double>::infinity();
  return std::sqrt(*fracture_energy * moments.m / (15.0 * shear * moments.m3));
}

double lps_equivalent_bulk(double bulk, double shear) { return 5.0 / 9.0 * (bulk + 4.0 / 3.0 * shear); }

}  // namespace ballista::pd
