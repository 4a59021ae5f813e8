#pragma once
// Shared helpers of the peridynamics verification problems (test_pd_wave_and_fracture.cpp, the
// default suite, and slow_pd_wave_speed.cpp, label slow): decks for a block of glass-like PMB
// material on a cubic lattice, lattice sums of the discretised model (its long-wave elastic
// constants and its fracture energy per unit area, independent of the solver), the longitudinal
// wave in a thin bar and the pre-cracked block pulled apart. Derivations in docs/validation.md
// ("Peridynamics: wave speed and energy release").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "deck/deck_reader.hpp"
#include "peridynamics/bond_family.hpp"
#include "peridynamics/pd_solver.hpp"
#include "run/simulation.hpp"
#include "verification/verification_support.hpp"

namespace ballista::verification::pdv {

// Material: E = 72 GPa, nu = 1/4 (the only Poisson ratio of bond-based PMB in 3D), rho = 2200 kg/m^3.
constexpr double kE = 72e9;          // Pa
constexpr double kNu = 0.25;         // 1
constexpr double kRho = 2200.0;      // kg/m^3
constexpr double kK = kE / 1.5;      // Pa, K = E/(3 (1 - 2 nu))
constexpr double kM = 3.0;           // horizon / lattice spacing (the solver's default)

inline std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

/// A box [lo, hi] of the material on the lattice of spacing dx (points at the cell centres of a
/// grid whose lower corner is -10 mm, a multiple of every dx used), grid box 10 mm beyond the body.
/// `nu`: the material's Poisson's ratio (a bond-based solid takes only its bulk modulus).
inline std::string box_deck(double dx, const double lo[3], const double hi[3], const std::string& pd,
                            double nu = kNu) {
  const double pad = 0.01;
  // The references below are sums with the continuum constants c = 18 K/(pi delta^4) and eq. 25's
  // s00: those constants unless the caller chooses the calibration.
  const std::string cal = pd.find("calibration") == std::string::npos ? "calibration: continuum, " : "";
  return "simulation: {solver: peridynamics, dimension: 3d, end_time: 1}\n"
         "peridynamics: {" + cal + pd + "}\n" +
         "grid: {lower: [" + num(-pad) + ", " + num(-pad) + ", " + num(-pad) + "], upper: [" + num(hi[0] + pad) +
         ", " + num(hi[1] + pad) + ", " + num(hi[2] + pad) + "], cell_size: " + num(dx) + "}\n" +
         "materials:\n  glass: {model: linear_elastic, density: " + num(kRho) + ", youngs_modulus: " + num(kE) +
         ", poisson_ratio: " + num(nu) + "}\n" +
         "bodies:\n  - {name: b, material: glass, shape: {type: box, lower: [" + num(lo[0]) + ", " + num(lo[1]) + ", " +
         num(lo[2]) + "], upper: [" + num(hi[0]) + ", " + num(hi[1]) + ", " + num(hi[2]) + "]}}\n";
}

inline std::unique_ptr<PdSolver> make_solver(const std::string& yaml) {
  const Scenario sc = parse_deck(yaml, "pd_verification.yaml");
  return std::make_unique<PdSolver>(sc, make_materials(sc));
}

/// Long-wave constants of the discretised PMB model on an infinite cubic lattice at m = delta/dx,
/// with the solver's partial-volume rule (bonds up to delta, the factor of pd::partial_volume_factor),
/// as ratios to the continuum PMB values. With c = 18 K/(pi delta^4) and linearised bond stretch
/// s = xi.eps.xi/|xi|^2 the energy density is W = (c/4) sum_j beta_j V (xi_j.eps.xi_j)^2/|xi_j|^3,
/// so C_abcd = (c V/2) sum_j beta_j xi_a xi_b xi_c xi_d/|xi_j|^3: a cubic crystal with
/// C11 = (cV/2) sum beta xi_x^4/|xi|^3 and C12 = C44 = (cV/2) sum beta xi_x^2 xi_y^2/|xi|^3
/// (continuum: C11 = 9K/5, C12 = 3K/5, i.e. lambda = mu = 3K/5, nu = 1/4). A thin bar along [100]
/// has E_100 = (C11 - C12)(C11 + 2 C12)/(C11 + C12) (continuum 3K/2 = E).
/// The fracture energy of the lattice: the bonds crossing a plane between two lattice layers, per
/// unit area, each at the critical stretch (energy c s0^2 |xi| beta V^2 / 2): a bond vector xi with
/// xi_z > 0 crosses the plane from xi_z/dx layers, 1/dx^2 points per layer, so
/// G_lattice = (c s0^2 V/2) sum_{xi_z > 0} beta |xi| xi_z, against the continuum integral of
/// Silling & Askari 2005 eq. 25, G0 = (c s0^2/2) int_{xi_z > 0} |xi| xi_z dV = pi c s0^2 delta^5/10.
struct LatticeConstants {
  double c11 = 0.0, c12 = 0.0;  ///< ratio to the continuum 9K/5 and 3K/5
  double e100 = 0.0;            ///< Young's modulus along [100] over E
  double nu100 = 0.0;           ///< Poisson ratio for a pull along [100], C12/(C11 + C12)
  double g = 0.0;               ///< G_lattice / G0 at the same s0
  double k = 0.0;               ///< bulk modulus over K
};

inline LatticeConstants lattice_constants(double m, bool partial = true) {
  double s11 = 0.0, s12 = 0.0, sg = 0.0, sk = 0.0;  // units of dx = 1
  const int r = static_cast<int>(std::ceil(m)) + 1;
  for (int i = -r; i <= r; ++i)
    for (int j = -r; j <= r; ++j)
      for (int k = -r; k <= r; ++k) {
        const double x = std::sqrt(double(i * i + j * j + k * k));
        if (x == 0.0) continue;
        // The solver's family: |xi| <= delta (to a relative 1e-9, bond_family.cpp), the factor of
        // pd::partial_volume_factor within dx/2 inside the horizon (LAMMPS PERI's rule).
        if (x > m * (1.0 + 1e-9)) continue;
        const double b = partial ? ballista::pd::partial_volume_factor(x, m, 1.0) : 1.0;
        s11 += b * std::pow(i, 4) / (x * x * x);
        s12 += b * double(i * i) * double(j * j) / (x * x * x);
        sk += b * x;
        if (k > 0) sg += b * x * k;
      }
  const double pi = std::numbers::pi, c = 18.0 / (pi * std::pow(m, 4));  // K = 1
  LatticeConstants lc;
  const double C11 = 0.5 * c * s11, C12 = 0.5 * c * s12;
  lc.c11 = C11 / 1.8;
  lc.c12 = C12 / 0.6;
  lc.e100 = (C11 - C12) * (C11 + 2 * C12) / (C11 + C12) / 1.5;
  lc.nu100 = C12 / (C11 + C12);
  lc.g = sg / (pi * std::pow(m, 5) / 5.0);
  lc.k = sk / (pi * std::pow(m, 4));
  return lc;
}

// --- Problem 1: longitudinal wave in a thin bar ---------------------------------------------------

/// Bar [0, L] x [0, w] x [0, w]; initial velocity v_x = V0 exp(-(X - X0)^2/(2 sigma^2)) (uniform over
/// the section, no displacement): it splits into two pulses of amplitude V0/2 running both ways.
/// Stations X1 < X2 on the right; the left-going pulse, reflected at X = 0, arrives 2 X0/c later and
/// the right-going one, reflected at X = L, returns 2 (L - X2)/c later: both >= 8 sigma/c behind
/// (where the Gaussian is exp(-8) of its peak), set below.
struct BarGeometry {
  double w = 4e-3;       ///< m, section side
  double sigma = 6e-3;   ///< m, pulse width
  double x0 = 24e-3;     ///< m, pulse centre (4 sigma from the free end)
  double x1 = 48e-3;     ///< m, first station (4 sigma from the pulse: its initial velocity there is exp(-8))
  double x2 = 72e-3;     ///< m, second station
  double length = 96e-3; ///< m, bar length (4 sigma beyond the second station)
};

struct WaveResult {
  double dx = 0.0, delta = 0.0;
  double xs1 = 0.0, xs2 = 0.0;  ///< m, reference positions of the two station slices
  double t1 = 0.0, t2 = 0.0;    ///< s, arrival (energy centroid) times
  double speed = 0.0;           ///< m/s
  long points = 0, steps = 0;
};

/// Index of the peak of v^2 among the samples with t <= t_max.
inline size_t peak_index(const std::vector<double>& t, const std::vector<double>& v, double t_max) {
  size_t ip = 0;
  for (size_t i = 0; i < v.size() && t[i] <= t_max; ++i)
    if (v[i] * v[i] > v[ip] * v[ip]) ip = i;
  return ip;
}

/// Energy-centroid arrival time of the pulse in a station record: t_a = sum t v^2 / sum v^2 over a
/// window of +-half_window around the peak time t_p (exact for a pulse of any shape travelling
/// without change; with dispersion, the arrival of the energy, i.e. at the mean group velocity).
inline double arrival_time(const std::vector<double>& t, const std::vector<double>& v, double t_p, double half_window) {
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < v.size(); ++i)
    if (std::abs(t[i] - t_p) <= half_window) {
      num += t[i] * v[i] * v[i];
      den += v[i] * v[i];
    }
  return num / den;
}

/// `pd`: further peridynamics keys (e.g. "formulation: lps"), `nu` the material's Poisson's ratio.
inline WaveResult measure_wave(double dx, const BarGeometry& g = {}, const std::string& pd = "", double nu = kNu) {
  const double lo[3] = {0, 0, 0}, hi[3] = {g.length, g.w, g.w};
  auto s = make_solver(box_deck(dx, lo, hi, "m: " + num(kM) + (pd.empty() ? "" : ", " + pd), nu));
  FieldStore& pts = s->points();
  const Index n = pts.size();
  const auto* x0 = pts.view<Vec3>("x0");
  auto* v = pts.view<Vec3>("v");
  const double v0 = 0.1;  // m/s: strain ~ v0/c ~ 2e-5, linear
  for (Index p = 0; p < n; ++p) {
    const double d = (x0[p][0] - g.x0) / g.sigma;
    v[p] = Vec3{{v0 * std::exp(-0.5 * d * d), 0.0, 0.0}};
  }
  s->refresh();
  // Station slices: the lattice layer nearest to X1 and X2 (their own X is used for the distance).
  auto layer = [&](double X) { return (std::floor(X / dx) + 0.5) * dx; };
  WaveResult r;
  r.dx = dx;
  r.delta = s->horizon();
  r.xs1 = layer(g.x1);
  r.xs2 = layer(g.x2);
  std::vector<Index> st[2];
  for (Index p = 0; p < n; ++p) {
    if (std::abs(x0[p][0] - r.xs1) < 0.25 * dx) st[0].push_back(p);
    if (std::abs(x0[p][0] - r.xs2) < 0.25 * dx) st[1].push_back(p);
  }
  const double c0 = std::sqrt(kE / kRho);
  // Long enough for the pulse to pass the second station at 0.75 c0 (the coarsest bar is ~15 % slow).
  const double t_end = (g.x2 - g.x0 + 4.0 * g.sigma) / (0.75 * c0);
  std::vector<double> t, vs[2];
  auto record = [&]() {
    t.push_back(s->time());
    for (int k = 0; k < 2; ++k) {
      double sum = 0.0;
      for (Index p : st[k]) sum += v[p][0];
      vs[k].push_back(sum / static_cast<double>(st[k].size()));
    }
  };
  record();
  while (s->time() < t_end) {
    s->step(s->stable_dt());
    record();
  }
  // The direct pulse peaks at a station by (X_s - X0)/(0.7 c0) (the coarsest bar runs at 0.75 c0);
  // the reflections from the ends cannot arrive before (X_s + X0)/c0 and (2 L - X_s - X0)/c0 (at
  // most c0), 2-3 us later: the peak is searched before the former. Window: +-4 sigma/c with c
  // from the two peak times (the pulse lasts ~ +-4 sigma/c at a station).
  const size_t p1 = peak_index(t, vs[0], (r.xs1 - g.x0) / (0.7 * c0));
  const size_t p2 = peak_index(t, vs[1], (r.xs2 - g.x0) / (0.7 * c0));
  const double c_est = (r.xs2 - r.xs1) / (t[p2] - t[p1]);
  const double half = 4.0 * g.sigma / c_est;
  r.t1 = arrival_time(t, vs[0], t[p1], half);
  r.t2 = arrival_time(t, vs[1], t[p2], half);
  r.speed = (r.xs2 - r.xs1) / (r.t2 - r.t1);
  r.points = static_cast<long>(n);
  r.steps = s->steps();
  return r;
}

/// Reference speed of the bar: the thin-bar speed sqrt(E_100/rho) of the discretised model (lattice
/// constants above), times the Rayleigh-Love lateral-inertia correction for the pulse (Graff,
/// "Wave motion in elastic solids", 1975, §2.13: omega^2 = c^2 k^2/(1 + nu^2 k^2 r_g^2), so the
/// group velocity is c (1 - 3/2 nu^2 k^2 r_g^2); the Gaussian's energy spectrum exp(-k^2 sigma^2) has
/// <k^2> = 1/(2 sigma^2); r_g^2 = w^2/6 for a square section): 1 - 3 nu^2 w^2/(24 sigma^2), 0.35 %.
inline double love_factor(const BarGeometry& g, double nu) { return 1.0 - 3.0 * nu * nu * g.w * g.w / (24.0 * g.sigma * g.sigma); }

/// The bar at dx = 1 and 0.5 mm against the lattice model's bar speed cm and the continuum's c0:
/// the table printed, the speeds, the observed order of the error against cm (p = 1 expected: the
/// bar's surface layer, a fraction ~ delta/w of its section) and the first-order Richardson
/// extrapolate 2 c(0.5 mm) - c(1 mm) reported under `name` (pd_wave_and_fracture: "pd_wave").
/// `pd` and `nu` as measure_wave's.
struct WaveStudy {
  std::vector<WaveResult> levels;  ///< dx = 1, 0.5 mm
  double error_coarse = 0.0, error_fine = 0.0;  ///< |c / cm - 1|
  double order = 0.0;
  double extrapolated = 0.0;  ///< m/s
};
inline WaveStudy wave_study(const BarGeometry& g, double cm, double c0, const std::string& name,
                            const std::string& pd = "", double nu = kNu) {
  WaveStudy st;
  std::printf("| dx (mm) | delta (mm) | w/delta | points | steps | speed (m/s) | error vs c_m | error vs c0 |\n");
  for (double dx : {1e-3, 0.5e-3}) {
    st.levels.push_back(measure_wave(dx, g, pd, nu));
    const WaveResult& w = st.levels.back();
    std::printf("| %.3f | %.3f | %.2f | %ld | %ld | %.1f | %+.2f %% | %+.2f %% |\n", w.dx * 1e3, w.delta * 1e3,
                g.w / w.delta, w.points, w.steps, w.speed, 100 * (w.speed / cm - 1), 100 * (w.speed / c0 - 1));
  }
  const WaveResult &a = st.levels[0], &b = st.levels[1];
  st.error_coarse = std::abs(a.speed / cm - 1);
  st.error_fine = std::abs(b.speed / cm - 1);
  st.order = observed_order(st.error_coarse, st.error_fine);
  st.extrapolated = 2.0 * b.speed - a.speed;
  report(name + "_speed_dx1mm", a.speed);
  report(name + "_speed_dx0.5mm", b.speed);
  report(name + "_order_vs_lattice", st.order);
  report(name + "_extrapolated_speed", st.extrapolated);
  std::printf("observed order %.2f; extrapolated speed %.1f m/s = c_m %+.2f %% = c0 %+.2f %%\n", st.order,
              st.extrapolated, 100 * (st.extrapolated / cm - 1), 100 * (st.extrapolated / c0 - 1));
  return st;
}

// --- Problem 2: energy release of a pre-cracked block ---------------------------------------------

struct FractureResult {
  double g_measured = 0.0;   ///< J/m^2: dissipated energy / ligament area
  double g_lattice = 0.0;    ///< J/m^2: the ligament's crossing bonds at exactly s0 / ligament area
  double area = 0.0;         ///< m^2
  long crossing = 0;         ///< bonds crossing the ligament
  long broken_crossing = 0;  ///< of those, broken at the end
  long broken_off = 0;       ///< bonds broken that do not cross the ligament (off the plane)
  double dissipated = 0.0, kinetic0 = 0.0;  ///< J
  double dissipated_floor = 0.0;  ///< J: the broken crossing bonds' energy at exactly s0 (a lower bound)
  double energy_error = 0.0;      ///< (E_total(t_end) - E_total(0)) / E_total(0) (dynamic)
  double t_end = 0.0;
};

/// A cube of side a (points (i + 1/2) dx) cut by the plane z = a/2 (between two lattice layers);
/// the pre-crack is that plane outside a central square ligament of side b: a bond is pre-broken
/// (PdSolver::break_bonds) when it crosses the plane at a point (x, y) outside the ligament. Then
/// the halves are pulled apart until every bond crossing the ligament is broken (or t_max):
///  - quasi_static: the halves move as rigid bodies, upper +u/2, lower -u/2 along z, and the
///    opening u visits exactly the critical openings of the lattice, u* with |xi + u* e_z| =
///    (1 + s0) |xi| for each crossing bond vector xi (times 1 + 1e-7), refreshing the forces at each:
///    every crossing bond breaks at s0 (1 + O(1e-7)), the limit of a slow separation;
///  - dynamic: the halves get velocities +-v z (v = v_over_s0c s0 c0) and the elastic halves and the
///    ligament evolve freely (velocity Verlet); the ligament tears.
inline FractureResult measure_fracture(double dx, double a, double b, double g0, bool quasi_static,
                                       double v_over_s0c = 0.0, double t_max = 0.0,
                                       const std::string& calibration = "continuum", const std::string& pd = "") {
  const double lo[3] = {0, 0, 0}, hi[3] = {a, a, a};
  auto s = make_solver(box_deck(dx, lo, hi,
                                "m: " + num(kM) + ", fracture_energy: " + num(g0) + ", calibration: " + calibration +
                                    (pd.empty() ? "" : ", " + pd)));
  FieldStore& pts = s->points();
  const Index n = pts.size();
  const auto* x0 = pts.view<Vec3>("x0");
  // Ligament edges dx/24 off the half-lattice: crossing points lie at x = (i + 1/2) dx + f xi_x with
  // f xi_x a multiple of dx/12 (|xi| <= 3 dx), so no crossing point sits on an edge and a ligament
  // of side b (a multiple of dx) holds exactly b/dx crossing points per row of each bond vector and
  // layer: the lattice sum per unit area is then exact, without edge effects.
  const double zc = 0.5 * a, l0 = 0.5 * (a - b) + dx / 24.0, l1 = l0 + b;
  // Where the bond p-q crosses the plane z = zc (false if it does not): (x, y) of the crossing.
  auto crossing_point = [&](const Vec3& p, const Vec3& q, double& x, double& y) {
    if (!((p[2] < zc) != (q[2] < zc))) return false;
    const double f = (zc - p[2]) / (q[2] - p[2]);
    x = p[0] + f * (q[0] - p[0]);
    y = p[1] + f * (q[1] - p[1]);
    return true;
  };
  auto in_ligament = [&](double x, double y) { return x > l0 && x < l1 && y > l0 && y < l1; };
  const long pre = static_cast<long>(s->break_bonds([&](const Vec3& p, const Vec3& q) {
    double x, y;
    return crossing_point(p, q, x, y) && !in_ligament(x, y);
  }));
  const double s0 = s->critical_stretch(0, 0), c = s->micromodulus(0, 0), V = dx * dx * dx;
  const ballista::pd::BondFamily& f = s->bonds();
  // The ligament's crossing bonds (each stored at both ends: counted from the lower end only), their
  // energy at exactly s0 (the lattice fracture energy of the ligament) and critical openings.
  std::vector<Index> lig;  // bond slots (lower end)
  std::vector<double> openings, e_s0;
  double e_lattice = 0.0;
  for (Index p = 0; p < n; ++p)
    for (Index k = f.offset[p]; k < f.offset[p + 1]; ++k) {
      const Index q = f.other[k];
      double x, y;
      if (x0[p][2] < zc && crossing_point(x0[p], x0[q], x, y) && in_ligament(x, y)) {
        lig.push_back(k);
        e_s0.push_back(0.5 * c * s0 * s0 * f.length0[k] * f.volume_factor[k] * V * V);
        e_lattice += e_s0.back();
        const Vec3 xi = x0[q] - x0[p];
        const double r = (1.0 + s0) * f.length0[k];
        openings.push_back(std::sqrt(r * r - xi[0] * xi[0] - xi[1] * xi[1]) - xi[2]);
      }
    }
  FractureResult res;
  res.area = b * b;
  res.crossing = static_cast<long>(lig.size());
  res.g_lattice = e_lattice / res.area;
  auto lig_broken = [&]() {
    long k = 0;
    for (Index slot : lig) k += f.broken[slot];
    return k;
  };
  if (quasi_static) {
    std::sort(openings.begin(), openings.end());
    auto* x = pts.view<Vec3>("x");
    double last = -1.0;
    for (double u : openings) {
      if (u < last * (1.0 + 1e-6)) continue;  // the same opening (another bond of the same family)
      last = u;
      const double uu = u * (1.0 + 1e-7);
      for (Index p = 0; p < n; ++p) x[p] = x0[p] + Vec3{{0.0, 0.0, x0[p][2] > zc ? 0.5 * uu : -0.5 * uu}};
      s->refresh();
    }
  } else {
    const double c0 = std::sqrt(kE / kRho), vz = v_over_s0c * s0 * c0;
    auto* v = pts.view<Vec3>("v");
    for (Index p = 0; p < n; ++p) v[p] = Vec3{{0.0, 0.0, x0[p][2] > zc ? vz : -vz}};
    s->refresh();
    res.kinetic0 = s->energies().kinetic;
    const double e0 = s->energies().total();
    while (s->time() < t_max && lig_broken() < res.crossing) s->step(s->stable_dt());
    res.energy_error = (s->energies().total() - e0) / e0;
  }
  for (size_t i = 0; i < lig.size(); ++i)
    if (f.broken[lig[i]]) res.dissipated_floor += e_s0[i];
  res.t_end = s->time();
  res.broken_crossing = lig_broken();
  res.broken_off = static_cast<long>(s->broken_bonds()) - pre - res.broken_crossing;
  res.dissipated = s->energies().plastic;
  res.g_measured = res.dissipated / res.area;
  return res;
}

}  // namespace ballista::verification::pdv
