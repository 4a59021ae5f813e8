#pragma once
// Shared helpers of the verification tests (tests/verification/*.cpp): load a shipped example deck
// with overrides, advance a solver exactly as `ballista run` does, temporary result folders,
// history.csv reading, convergence orders and reporting (stdout + gtest XML properties).
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/solver.hpp"
#include "deck/deck_reader.hpp"
#include "materials/elastic_constants.hpp"
#include "points/mms_axis_aligned.hpp"
#include "points/mms_generalized_vortex.hpp"
#include "run/simulation.hpp"

namespace ballista::verification {

/// Path of a shipped deck, examples/<name>.
inline std::string example_path(const std::string& name) {
  return (std::filesystem::path(BALLISTA_SOURCE_DIR) / "examples" / name).string();
}

/// Reads examples/<name> with --set style overrides.
inline Scenario load_example(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return read_deck(example_path(name), overrides);
}

/// "key=value" with the value printed to full precision.
inline std::string set_number(const std::string& key, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return key + "=" + buf;
}

/// The points' total momentum along axis `a`, sum m_p v_p[a] (kg m/s; per radian in axisymmetry).
inline double total_momentum(const FieldStore& pts, int a = 0) {
  const auto* v = pts.view<Vec3>("v");
  const auto* m = pts.real("mass");
  double sum = 0.0;
  for (Index p = 0; p < pts.size(); ++p) sum += m[p] * v[p][a];
  return sum;
}

/// Advances the solver to `end` with the time-step choice of run_simulation (src/run/simulation.cpp):
/// dt = stable_dt(), shortened to land exactly on every multiple of `interval` (the deck's
/// output.interval; 0 = none) and on `end`. Landing on the same times as `ballista run` makes the
/// numbers below reproducible with the command line.
inline void advance(Solver& solver, double end, double interval = 0.0) {
  const double iv = interval > 0 ? interval : end;
  double next = iv;
  while (solver.time() < end * (1.0 - 1e-12)) {
    double dt = solver.stable_dt();
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::runtime_error("time step collapsed");
    dt = std::min({dt, end - solver.time(), next - solver.time()});
    solver.step(dt);
    if (solver.time() >= next * (1.0 - 1e-12)) next = std::min(next + iv, end);
  }
}

/// Mass-weighted mean radial velocity of the points keep(p) selects, m/s: about the z axis
/// (3D, plane strain), or v_r = v_x in an axisymmetric run (x the radius).
template <class Keep>
double mean_radial_velocity(const FieldStore& pts, bool axisymmetric, Keep&& keep) {
  const auto* x = pts.view<Vec3>("x");
  const auto* v = pts.view<Vec3>("v");
  const auto* m = pts.real("mass");
  double mv = 0.0, mm = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    if (!keep(p)) continue;
    mv += axisymmetric ? m[p] * v[p][0]
                       : m[p] * (v[p][0] * x[p][0] + v[p][1] * x[p][1]) / std::hypot(x[p][0], x[p][1]);
    mm += m[p];
  }
  return mv / mm;
}

/// Steps to `end` at the solver's stable step (the last one shortened to end there, 1e-15 s past to
/// absorb round-off) and returns the largest |total energy - initial total| after any step, J: the
/// worst energy residual of the run (EnergyTotals::total, the balance every solver books).
inline double run_worst_energy_residual(Solver& solver, double end) {
  const double total0 = solver.energies().total();
  double worst = 0.0;
  while (solver.time() < end) {
    solver.step(std::min(solver.stable_dt(), end - solver.time() + 1e-15));
    worst = std::max(worst, std::abs(solver.energies().total() - total0));
  }
  return worst;
}

/// A fresh folder under the system temp directory, removed at scope exit (kept if the environment
/// variable BALLISTA_KEEP_TEST_OUTPUT is set, to inspect the results).
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    static std::atomic<int> counter{0};
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = "ballista_ver_" + tag + "_" + std::to_string(::getpid()) + "_" +
                       std::to_string(counter++);
    if (info) name += std::string("_") + info->name();
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    if (std::getenv("BALLISTA_KEEP_TEST_OUTPUT")) {
      std::printf("kept test output in %s\n", path_.string().c_str());
      return;
    }
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string str() const { return path_.string(); }
  std::filesystem::path path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// Runs the scenario with the real driver (run_simulation) into `dir`, quietly.
inline RunResult run_into(const Scenario& sc, const std::string& dir, int threads = 0) {
  RunOptions opt;
  opt.out_dir = dir;
  opt.progress = false;
  opt.threads = threads;
  return run_simulation(sc, opt);
}

/// history.csv as columns (name -> values in row order).
struct History {
  std::map<std::string, std::vector<double>> columns;
  size_t rows = 0;
  const std::vector<double>& operator[](const std::string& name) const {
    auto it = columns.find(name);
    if (it == columns.end()) throw std::runtime_error("history.csv has no column '" + name + "'");
    return it->second;
  }
};

inline History read_history(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) names.push_back(cell);
  }
  History h;
  for (const auto& n : names) h.columns[n];
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::string cell;
    size_t k = 0;
    while (std::getline(ss, cell, ',') && k < names.size()) h.columns[names[k++]].push_back(std::strtod(cell.c_str(), nullptr));
    if (k != names.size()) throw std::runtime_error("short row in " + path);
    ++h.rows;
  }
  return h;
}

/// Observed order of convergence from errors at sizes h and h / ratio.
inline double observed_order(double e_coarse, double e_fine, double ratio = 2.0) {
  return std::log(e_coarse / e_fine) / std::log(ratio);
}

/// Prints "name = value" to stdout (visible with ctest -V / --output-on-failure) and records it
/// as a property of the current test (in the gtest XML report).
inline void report(const std::string& name, double value) {
  std::printf("  %-40s = %.6g\n", name.c_str(), value);
  std::fflush(stdout);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  ::testing::Test::RecordProperty(name, buf);
}

// ---------------------------------------------------------------------------------------------
// B3 thick-walled cylinder (test_b3_thick_cylinder.cpp, slow_b3_thick_cylinder_sweep.cpp).

/// Plane-strain Lame solution for a tube with inner radius a (traction free) and outer radius b
/// under external pressure P: u_r(r) = -(1 + nu) P b^2 / (E (b^2 - a^2)) ((1 - 2 nu) r + a^2 / r)
/// (derivation in docs/validation.md, B3).
inline double lame_ur(double r, double a, double b, double P, double E, double nu) {
  return -(1.0 + nu) * P * b * b / (E * (b * b - a * a)) * ((1.0 - 2.0 * nu) * r + a * a / r);
}

struct CylinderError {
  double rel_l2 = 0.0;   ///< sqrt(sum (u_s - u_e)^2 / sum u_e^2) over particles
  double rms = 0.0;      ///< thesis eq. 6.4: sqrt(sum (u_s - u_e)^2 / N), m
  double max_rel = 0.0;  ///< max |u_s - u_e| / max |u_e|
  double ke_over_ie = 0.0;  ///< kinetic / internal energy at the end (settling check)
  /// Mean signed (u_s - u_e)/u_e of the particles within 10 degrees of a symmetry plane
  /// (theta < 10 or > 80 degrees) and within 10 degrees of the 45-degree diagonal.
  double mean_rel_planes = 0.0, mean_rel_diagonal = 0.0;
  double nu = 0.0, E = 0.0;
  long particles = 0;
  long steps = 0;
};

/// Runs a thick-cylinder scenario (examples/thick_cylinder.yaml layout: body 0 a tube around the
/// z axis, load 0 the outer pressure, held at its final value) to its end time and compares the
/// radial displacement u_r = (x - x0) . r_hat with lame_ur at the reference radius |x0| (the
/// strains are ~1e-4, so reference and current radius differ by far less than the error).
inline CylinderError run_thick_cylinder(const Scenario& sc) {
  auto solver = make_solver(sc);
  advance(*solver, sc.simulation.end_time, sc.output.interval);
  const ElasticConstants ec = elastic_constants_from(sc.materials.at(0).params);
  const double K = ec.bulk, G = ec.shear;
  CylinderError e;
  e.E = 9.0 * K * G / (3.0 * K + G);
  e.nu = (3.0 * K - 2.0 * G) / (2.0 * (3.0 * K + G));
  const double a = sc.bodies.at(0).shape.inner_radius, b = sc.bodies.at(0).shape.radius;
  const double P = sc.loads.at(0).params.at("pressure") * sc.loads.at(0).curve.at(solver->time());
  const FieldStore& pts = solver->points();
  const Vec3* x = pts.view<Vec3>("x");
  const Vec3* X = pts.view<Vec3>("x0");
  double num = 0.0, den = 0.0, maxerr = 0.0, maxex = 0.0;
  double band[2] = {0.0, 0.0};
  long in_band[2] = {0, 0};
  for (Index p = 0; p < pts.size(); ++p) {
    const double r = std::hypot(X[p][0], X[p][1]);
    const double us = ((x[p][0] - X[p][0]) * X[p][0] + (x[p][1] - X[p][1]) * X[p][1]) / r;
    const double ue = lame_ur(r, a, b, P, e.E, e.nu);
    const double deg = std::atan2(X[p][1], X[p][0]) * 180.0 / 3.14159265358979323846;
    const int k = deg < 10.0 || deg > 80.0 ? 0 : (std::abs(deg - 45.0) < 10.0 ? 1 : -1);
    if (k >= 0) {
      band[k] += (us - ue) / ue;
      ++in_band[k];
    }
    num += (us - ue) * (us - ue);
    den += ue * ue;
    maxerr = std::max(maxerr, std::abs(us - ue));
    maxex = std::max(maxex, std::abs(ue));
  }
  e.particles = static_cast<long>(pts.size());
  e.steps = solver->steps();
  e.rel_l2 = std::sqrt(num / den);
  e.rms = std::sqrt(num / static_cast<double>(pts.size()));
  e.max_rel = maxerr / maxex;
  e.mean_rel_planes = band[0] / static_cast<double>(std::max(in_band[0], 1L));
  e.mean_rel_diagonal = band[1] / static_cast<double>(std::max(in_band[1], 1L));
  const EnergyTotals en = solver->energies();
  e.ke_over_ie = en.kinetic / en.internal;
  return e;
}

/// Table 6.2 moduli of thesis seed 000: the sweep by K holds G = 26.23 GPa, the sweep by G holds
/// K = 70.28 GPa.
constexpr double kCylinderG0 = 26.23e9;  // Pa
constexpr double kCylinderK0 = 70.28e9;  // Pa
inline double bulk_for_nu(double nu, double G) { return 2.0 * G * (1.0 + nu) / (3.0 * (1.0 - 2.0 * nu)); }
inline double shear_for_nu(double nu, double K) { return 3.0 * K * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu)); }

/// examples/thick_cylinder.yaml at cell size h with moduli K, G (plus further overrides). The
/// deck's pressure ramp (3 ms), damping (3000 /s) and end time (6 ms) are tuned for G = 26.23 GPa;
/// the quasi-static settling is governed by the shear (isochoric) response, so for a smaller G
/// they are stretched by the shear-wave-speed ratio s = sqrt(G0 / G): ramp 3 ms s, end 6 ms s,
/// damping 3000 / s. (Checked at h = 0.1 by G: doubling the end time changes the relative error by
/// at most 0.2 percentage points at nu = 0.45 and 0.499.) The pressure is scaled by the same
/// min(1, G / G0): the Lame solution is small-strain, and at 10 MPa and G = 0.14 GPa (nu = 0.499 by
/// G) the hoop strain at the bore reaches 3 %, where the geometric nonlinearity alone moves u_r by
/// several per cent (measured at nu = 0.499, h = 0.1 -> 0.05: F-bar 3.4 % -> 4.9 % at 10 MPa but
/// 3.9 % -> 1.8 % at 0.1 MPa; the relative error of a linear response does not depend on P).
inline Scenario thick_cylinder_deck(double h, double K, double G, std::vector<std::string> more = {}) {
  const double s = G < kCylinderG0 ? std::sqrt(kCylinderG0 / G) : 1.0;
  const double p_scale = G < kCylinderG0 ? G / kCylinderG0 : 1.0;
  char curve[128];
  std::snprintf(curve, sizeof curve, "loads.0.curve=[[0, 0], [%.17g, 1], [100, 1]]", 3.0e-3 * s);
  std::vector<std::string> o = {set_number("grid.cell_size", h),
                                set_number("materials.aluminium_like.bulk_modulus", K),
                                set_number("materials.aluminium_like.shear_modulus", G),
                                set_number("simulation.end_time", 6.0e-3 * s),
                                set_number("simulation.damping", 3000.0 / s), curve, "output.interval=0"};
  if (p_scale < 1.0) o.push_back(set_number("loads.0.pressure", 10.0e6 * p_scale));
  o.insert(o.end(), more.begin(), more.end());
  return load_example("thick_cylinder.yaml", o);
}

// ---------------------------------------------------------------------------------------------
// B1 axis-aligned MMS (test_b1_axis_aligned_mms.cpp, slow_b1_axis_aligned_mms.cpp).

struct MmsError {
  double l2 = 0.0;    ///< RMS over particles of |x_p - (X_p + u(X_p, t))|, m
  double linf = 0.0;  ///< max over particles, m
  long particles = 0;
  long steps = 0;
};

/// Runs `sc` to its end time (landing on its output times) and measures |x_p - exact(X_p, t)|
/// over the particles (X_p the reference position "x0"): RMS and maximum.
template <class ExactPosition>
MmsError run_mms_error(const Scenario& sc, const ExactPosition& exact) {
  auto solver = make_solver(sc);
  advance(*solver, sc.simulation.end_time, sc.output.interval);
  const FieldStore& pts = solver->points();
  const Vec3* x = pts.view<Vec3>("x");
  const Vec3* X = pts.view<Vec3>("x0");
  const double t = solver->time();
  MmsError e;
  double sum = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    const double d = norm(x[p] - exact(X[p], t));
    sum += d * d;
    e.linf = std::max(e.linf, d);
  }
  e.particles = static_cast<long>(pts.size());
  e.l2 = std::sqrt(sum / static_cast<double>(pts.size()));
  e.steps = solver->steps();
  return e;
}

/// Runs the example deck at `cell_size` (plus any further --set overrides) to its end time and
/// measures the displacement error against the analytic u of src/points/mms_axis_aligned.hpp at
/// the reference positions "x0".
inline MmsError run_mms(double cell_size, const std::vector<std::string>& more = {}) {
  std::vector<std::string> o = {set_number("grid.cell_size", cell_size)};
  o.insert(o.end(), more.begin(), more.end());
  const Scenario sc = load_example("axis_aligned_mms.yaml", o);
  const mms::AxisAligned exact;
  return run_mms_error(sc, [&](const Vec3& X, double t) { return X + exact.displacement(X, t); });
}

// ---------------------------------------------------------------------------------------------
// B2 generalized vortex MMS (test_b2_generalized_vortex_mms.cpp, slow_b2_generalized_vortex_mms.cpp).

/// Runs examples/generalized_vortex_mms.yaml at `cell_size` with the given shape function (and any
/// further --set overrides) to its end time and measures |x_p - Q(alpha(R_p, t)) X_p| over the
/// particles (src/points/mms_generalized_vortex.hpp).
inline MmsError run_vortex(double cell_size, const std::string& shape_function,
                           const std::vector<std::string>& extra = {}) {
  std::vector<std::string> o = {set_number("grid.cell_size", cell_size), "mpm.shape_function=" + shape_function};
  o.insert(o.end(), extra.begin(), extra.end());
  const Scenario sc = load_example("generalized_vortex_mms.yaml", o);
  const mms::GeneralizedVortex exact;
  return run_mms_error(sc, [&](const Vec3& X, double t) { return exact.position(X, t); });
}

// ---------------------------------------------------------------------------------------------
// B6 Taylor bar (test_b6_taylor_bar.cpp, slow_b6_taylor_bar.cpp).

constexpr double kRho = 8930.0, kR0 = 3.2e-3, kL0 = 32.4e-3, kV0 = 227.0;

/// Analytic initial kinetic energy of the whole bar, 1/2 rho pi R0^2 L0 v0^2 = 239.81 J.
inline double ke0_whole_bar() { return 0.5 * kRho * std::numbers::pi * kR0 * kR0 * kL0 * kV0 * kV0; }

inline double probe(const RunResult& r, const std::string& name) {
  for (const auto& [n, v] : r.probes)
    if (n == name) return v;
  ADD_FAILURE() << "no probe " << name;
  return NAN;
}

struct TaylorFigures {
  double L = 0, R = 0, eqps = 0;   // m, m, 1
  double ke0 = 0, mass0 = 0;       // J and kg of the simulated part (whole bar or quarter)
  double balance = 0;              // |E_total(end) - E_total(0)| / E_total(0)
  double worst_balance = 0;        // max over the history rows
  double ke_end = 0, internal_end = 0, plastic_end = 0;
  long steps = 0;
};

inline TaylorFigures run_taylor(const Scenario& sc, const char* tag) {
  TempDir dir(tag);
  const RunResult r = run_into(sc, dir.str());
  EXPECT_TRUE(r.ok) << r.error;
  const History h = read_history((dir.path() / "history.csv").string());
  TaylorFigures f;
  f.L = probe(r, "final_length");
  f.R = probe(r, "foot_radius");
  f.eqps = probe(r, "max_eqps");
  f.steps = r.steps;
  f.ke0 = h["kinetic_energy"].front();
  f.mass0 = h["mass"].front();
  const auto& E = h["total_energy"];
  f.balance = std::abs(E.back() - E.front()) / E.front();
  for (double e : E) f.worst_balance = std::max(f.worst_balance, std::abs(e - E.front()) / E.front());
  f.ke_end = h["kinetic_energy"].back();
  f.internal_end = h["internal_energy"].back();
  f.plastic_end = h["plastic_work"].back();
  std::printf("%s: %ld steps\n", tag, f.steps);
  report(std::string(tag) + "_final_length_mm", 1e3 * f.L);
  report(std::string(tag) + "_foot_radius_mm", 1e3 * f.R);
  report(std::string(tag) + "_max_eqps", f.eqps);
  report(std::string(tag) + "_KE0_J", f.ke0);
  report(std::string(tag) + "_KE_end_J", f.ke_end);
  report(std::string(tag) + "_internal_end_J", f.internal_end);
  report(std::string(tag) + "_plastic_work_end_J", f.plastic_end);
  report(std::string(tag) + "_energy_balance_end_rel", f.balance);
  report(std::string(tag) + "_energy_balance_worst_rel", f.worst_balance);
  return f;
}

/// Acceptance bands of docs/validation.md ("Taylor bar", recommended bands for an MPM run at
/// 80 us): the spread of the published FE results (L_f 21.42-21.48 mm, R_f 7.11-7.29 mm for the
/// sources read) widened by the expected MPM measurement offsets and locking (-2 %/+2.7 % on L_f,
/// -6 %/+5 % on R_f). eqps has no verified published value (diagnostic band 2.3-3.8).
inline void expect_in_acceptance_bands(const TaylorFigures& f) {
  EXPECT_GE(f.L, 21.0e-3);
  EXPECT_LE(f.L, 22.0e-3);
  EXPECT_GE(f.R, 6.8e-3);
  EXPECT_LE(f.R, 7.6e-3);
  EXPECT_GE(f.eqps, 2.3);
  EXPECT_LE(f.eqps, 3.8);
}

}  // namespace ballista::verification
