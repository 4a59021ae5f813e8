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
  for_each_lattice_bond(delta, dx, partial, 3, [&](double x, double r, double b, double V) {
    m.m += r * r * b * V;
    if (x > 0.0) m.m3 += x * r * r * b * V;
  });
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
