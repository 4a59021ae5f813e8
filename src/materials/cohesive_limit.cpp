#include "materials/cohesive_limit.hpp"

#include <cmath>
#include <limits>

namespace ballista {

namespace {
/// x = (V/V0)^(1/3) at the limit: the positive root of eta x^2 + (1 - eta) x - 2 = 0
/// (cohesive_limit.hpp).
double spinodal_x(double eta) {
  return ((eta - 1.0) + std::sqrt((eta - 1.0) * (eta - 1.0) + 8.0 * eta)) / (2.0 * eta);
}
}  // namespace

double vinet_cohesive_volume_ratio(double k0p) {
  const double x = spinodal_x(1.5 * (k0p - 1.0));
  return x * x * x;
}

double vinet_cohesive_limit(double k0, double k0p) {
  const double eta = 1.5 * (k0p - 1.0);
  const double x = spinodal_x(eta);
  return 3.0 * k0 * (1.0 - x) / (x * x) * std::exp(eta * (1.0 - x));
}

double mie_gruneisen_cohesive_limit(const Eos& e) {
  const double k0p = 4.0 * e.s - 1.0;
  if (e.kind != Eos::Kind::MieGruneisen || !(k0p > 1.0)) return -std::numeric_limits<double>::infinity();
  return vinet_cohesive_limit(e.rho0 * e.c0 * e.c0, k0p);
}

}  // namespace ballista
