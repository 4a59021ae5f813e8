// The constants of the PMB bond from a material's elastic moduli (formulas and sources in
// bond_constants.hpp).
#include "peridynamics/bond_constants.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "geometry/seeding.hpp"

namespace ballista {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

ProbedModuli probe_moduli(const Material& material) {
  // One point, driven by a volumetric and then (from the start again) a shear velocity gradient
  // over dt = 1 s: for any model, at the reference state and for an increment of 1e-7 far inside
  // the elastic range, sigma = K tr(eps) I + 2 G dev(eps) to O(1e-7).
  constexpr double e = 1e-7;
  auto drive = [&](const Mat3& L) {
    FieldStore s;
    declare_point_fields(s);
    material.declare_fields(s);
    s.resize(1);
    material.initialise_state(s, 0, 1);
    s.real(kMass)[0] = material.density();
    s.real(kReferenceVolume)[0] = 1.0;
    s.real(kVolume)[0] = 1.0;
    s.view<Mat3>("R")[0] = Mat3::identity();
    Mat3& F = s.view<Mat3>("F")[0];
    F = (Mat3::identity() + L) * Mat3::identity();
    s.view<Mat3>("L")[0] = L;
    static const Index kPoint[1] = {0};
    material.update(make_batch(s, kPoint, 1, 1.0, false));
    return s.view<Mat3>("stress")[0];
  };
  // The adapter's midpoint increment of G = dt L is D dt = sym(G (I + G/2)^-1) (strain_increment.hpp).
  const double eps_vol = e / (1.0 + 0.5 * e);
  const Mat3 sv = drive(Mat3::diag(e, e, e));
  Mat3 shear;
  shear(0, 1) = shear(1, 0) = e;
  const Mat3 ss = drive(shear);
  ProbedModuli m;
  m.bulk = (sv(0, 0) + sv(1, 1) + sv(2, 2)) / (9.0 * eps_vol);
  m.shear = ss(0, 1) / (2.0 * e);
  return m;
}

namespace pd {

LatticeMoments calibration_moments(bool lattice, double delta, double dx, bool partial, int dim) {
  if (lattice) return lattice_moments(delta, dx, partial, dim);
  LatticeMoments m;
  m.m1 = dim == 3 ? std::numbers::pi * std::pow(delta, 4) : 2.0 * std::numbers::pi * std::pow(delta, 3) / 3.0;
  m.m2 = dim == 3 ? std::numbers::pi * std::pow(delta, 5) / 5.0 : std::pow(delta, 4) / 2.0;
  return m;
}

double dilatational_modulus(const ProbedModuli& moduli, int dim, bool plane_stress) {
  if (dim != 2) return moduli.bulk;
  const double E = 9.0 * moduli.bulk * moduli.shear / (3.0 * moduli.bulk + moduli.shear);
  const double nu = (3.0 * moduli.bulk - 2.0 * moduli.shear) / (2.0 * (3.0 * moduli.bulk + moduli.shear));
  return plane_stress ? E / (2.0 * (1.0 - nu)) : moduli.bulk + moduli.shear / 3.0;
}

double micromodulus(double kd, double m1, int dim) { return (dim == 3 ? 18.0 * kd : 8.0 * kd) / m1; }

double critical_stretch(std::optional<double> given, std::optional<double> fracture_energy, double c, double m2,
                        double yield_stretch) {
  if (given) return *given;
  if (!fracture_energy) return kInf;
  const double elastic = std::sqrt(2.0 * *fracture_energy / (c * m2));
  if (elastic <= yield_stretch) return elastic;  // breaks before it yields
  return *fracture_energy / (c * m2 * yield_stretch) + 0.5 * yield_stretch;
}

double yield_stretch(double yield_stress, const std::vector<double>& kd, const std::vector<std::uint8_t>& gas,
                     int dim) {
  double e_min = kInf;
  for (size_t a = 0; a < kd.size(); ++a)
    if (!gas[a]) e_min = std::min(e_min, dim == 3 ? 1.5 * kd[a] : 4.0 / 3.0 * kd[a]);
  return yield_stress / e_min;
}

double micro_plastic_flow_factor(int dim) {
  if (dim == 3) {
    const double a = 2.0 * std::cos(4.0 * std::numbers::pi / 9.0);
    return 2.0 * (1.0 - 2.0 * a * a * a);
  }
  // phi0 - sin(2 phi0)/2 = pi/4 by Newton from 1.15 (the left side grows monotonically on
  // (0, pi/2), its slope 1 - cos(2 phi0) = 2 sin^2 phi0 > 0; converged in four iterations).
  double phi = 1.15;
  for (int it = 0; it < 8; ++it)
    phi -= (phi - 0.5 * std::sin(2.0 * phi) - 0.25 * std::numbers::pi) / (1.0 - std::cos(2.0 * phi));
  return 6.0 / std::numbers::pi * (phi - 0.25 * std::numbers::pi + 0.5 * std::sin(2.0 * phi));
}

PairConstants pair_constants(const std::vector<double>& c, const std::vector<double>& s00,
                             const std::vector<std::uint8_t>& gas) {
  const size_t nmat = c.size();
  PairConstants k;
  k.c.resize(nmat * nmat);
  k.c_contact.resize(k.c.size());
  k.s00.resize(k.c.size());
  for (size_t a = 0; a < nmat; ++a)
    for (size_t b = 0; b < nmat; ++b) {
      const size_t ab = a * nmat + b;
      const bool any_gas = gas[a] || gas[b];
      k.c[ab] = any_gas ? 0.0 : 2.0 * c[a] * c[b] / (c[a] + c[b]);
      k.s00[ab] = any_gas ? kInf : std::min(s00[a], s00[b]);
      k.c_contact[ab] = gas[a] && gas[b] ? 0.0 : gas[a] ? c[b] : gas[b] ? c[a] : k.c[ab];
    }
  return k;
}

std::vector<double> surface_factors(const BondFamily& bonds, Index n, const double* vol0, double m1) {
  std::vector<double> factor(static_cast<size_t>(n), 1.0);
  for_each(0, n, [&](Index p) {
    double m1p = 0.0;
    for (Index k = bonds.offset[p]; k < bonds.offset[p + 1]; ++k)
      m1p += bonds.length0[k] * bonds.volume_factor[k] * vol0[bonds.other[k]];
    if (m1p > 0.0) factor[p] = m1 / m1p;
  });
  return factor;
}

}  // namespace pd
}  // namespace ballista
