#pragma once
// The B4 cantilever's references and its run (test_b4_cantilever.cpp, slow_b4_cantilever.cpp): the
// beam data of examples/cantilever_beam.yaml, the Euler-Bernoulli and Timoshenko first-mode
// periods, and the MPM run's period from the tip displacement. Apart from verification_support.hpp
// because the Timoshenko reference's dense eigensolver (Eigen) costs every file that includes it
// ten seconds of compilation.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "verification/verification_support.hpp"

namespace ballista::verification {


/// Beam data of examples/cantilever_beam.yaml (body 0 a box from the clamped face x_min) in the
/// plane-strain beam theories: E' = E / (1 - nu^2) (plane strain: the beam is a plate strip in
/// cylindrical bending, the plate modulus D = E' H^3 / 12), I = H^3/12 and A = H per unit thickness.
struct BeamData {
  double L = 0, H = 0, rho = 0, E = 0, nu = 0, G = 0;
  double E_plane() const { return E / (1.0 - nu * nu); }
};

inline BeamData beam_data(const Scenario& sc) {
  const ShapeSpec& s = sc.bodies.at(0).shape;
  const ElasticConstants ec = elastic_constants_from(sc.materials.at(0).params);
  BeamData b;
  b.L = s.upper[0] - s.lower[0];
  b.H = s.upper[1] - s.lower[1];
  b.rho = sc.materials.at(0).params.at("density");
  b.G = ec.shear;
  b.E = 9.0 * ec.bulk * ec.shear / (3.0 * ec.bulk + ec.shear);
  b.nu = (3.0 * ec.bulk - 2.0 * ec.shear) / (2.0 * (3.0 * ec.bulk + ec.shear));
  return b;
}

/// Euler-Bernoulli first-mode period of a cantilever: f1 = (beta1 L)^2 / (2 pi L^2) sqrt(E I / (rho A)),
/// beta1 L = 1.87510407 (Blevins 1979, Table 8-1; the brief's 1.875^2).
inline double euler_bernoulli_period(const BeamData& b) {
  const double bl = 1.8751040687119611;
  const double f = bl * bl / (2.0 * std::numbers::pi * b.L * b.L) * std::sqrt(b.E_plane() * b.H * b.H / 12.0 / b.rho);
  return 1.0 / f;
}

/// Timoshenko first-mode period (shear deformation with coefficient kappa and rotary inertia;
/// Timoshenko, Phil. Mag. 41 (1921) 744) by a 1D finite-element model: n two-node elements with
/// linear w and theta, the shear term integrated at one point (reduced integration: no locking of
/// the 1D model), consistent translational and rotary mass, clamped at x = 0; the lowest eigenvalue
/// of K q = omega^2 M q. Linear elements converge at O(1/n^2) (2.5e-4 of the period at n = 400 in
/// the Euler-Bernoulli limit), so timoshenko_period extrapolates from n = 200 and 400. kappa = 5/6 for a rectangle (Cowper, J. Appl. Mech. 33 (1966) 335 gives
/// 10(1 + nu)/(12 + 11 nu) = 0.850 at nu = 0.3, a 0.1 % change of the period here).
/// shear_rigid = true drops shear and rotary inertia: the Euler-Bernoulli limit (a check of the model).
inline double timoshenko_period_fe(const BeamData& b, double kappa, bool shear_rigid, int n) {
  // The Euler-Bernoulli limit as a penalty: shear stiffness 1e7 EI / L^2 and 1e-6 of the rotary
  // inertia change the period by ~2e-7 (measured: the bias falls as 1 / penalty).
  const double EI = b.E_plane() * b.H * b.H * b.H / 12.0, kGA = shear_rigid ? 1e7 * EI / (b.L * b.L) : kappa * b.G * b.H;
  const double rA = b.rho * b.H, rI = (shear_rigid ? 1e-6 : 1.0) * b.rho * b.H * b.H * b.H / 12.0;
  const double le = b.L / n;
  const int nd = 2 * (n + 1);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nd, nd), M = Eigen::MatrixXd::Zero(nd, nd);
  for (int e = 0; e < n; ++e) {
    const int d[4] = {2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3};  // w1, theta1, w2, theta2
    const double Bb[4] = {0.0, -1.0 / le, 0.0, 1.0 / le};        // theta'
    const double Bs[4] = {-1.0 / le, -0.5, 1.0 / le, -0.5};      // w' - theta at the midpoint
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) K(d[i], d[j]) += le * (EI * Bb[i] * Bb[j] + kGA * Bs[i] * Bs[j]);
    for (int a = 0; a < 2; ++a)
      for (int c = 0; c < 2; ++c) {
        const double m = le / 6.0 * (a == c ? 2.0 : 1.0);
        M(d[2 * a], d[2 * c]) += rA * m;
        M(d[2 * a + 1], d[2 * c + 1]) += rI * m;
      }
  }
  // Clamp: drop w and theta of node 0.
  const Eigen::MatrixXd Kc = K.bottomRightCorner(nd - 2, nd - 2), Mc = M.bottomRightCorner(nd - 2, nd - 2);
  // The dense solver's smallest eigenvalue carries round-off of order eps lambda_max / lambda_min
  // (1e-4..1e-3 with the shear penalty, and it changed with the compiler flags); three steps of
  // inverse iteration on its eigenvector and the Rayleigh quotient (error quadratic in the vector's)
  // bring it to ~1e-7 under every build.
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kc, Mc);
  Eigen::VectorXd v = es.eigenvectors().col(0);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(Kc);
  for (int it = 0; it < 3; ++it) {
    v = ldlt.solve(Mc * v);
    v.normalize();
  }
  const double lambda = v.dot(Kc * v) / v.dot(Mc * v);
  return 2.0 * std::numbers::pi / std::sqrt(lambda);
}

/// timoshenko_period_fe at n = 200 and 400, Richardson-extrapolated for its O(1/n^2) error:
/// T = (4 T_400 - T_200) / 3.
inline double timoshenko_period(const BeamData& b, double kappa = 5.0 / 6.0, bool shear_rigid = false) {
  return (4.0 * timoshenko_period_fe(b, kappa, shear_rigid, 400) - timoshenko_period_fe(b, kappa, shear_rigid, 200)) / 3.0;
}

struct CantileverResult {
  double period = 0.0;        ///< s, from the zero crossings of the tip displacement
  int crossings = 0;
  double amplitude = 0.0;     ///< m, largest |tip displacement|
  double energy_drift = 0.0;  ///< max_t |E(t) - E(0)| / E(0), E = kinetic + internal
  double energy_end = 0.0;    ///< (E(end) - E(0)) / E(0)
  long particles = 0;
  long steps = 0;
  std::string failure;        ///< the solver's error if the run stopped (e.g. J <= 0), else empty
  double failed_at = NAN;     ///< s
};

/// Runs examples/cantilever_beam.yaml at `cell_size` with `shape_function` and any further --set
/// overrides (e.g. "mpm.anti_locking=fbar"), recording after every step the tip displacement (the
/// mean y displacement of the particles of the last cell column, x0 > L - cell_size) and the energy.
/// The period is twice the mean spacing of the tip displacement's zero crossings (linear
/// interpolation between steps), skipping the start at t = 0.
inline CantileverResult run_cantilever(double cell_size, const std::string& shape_function,
                                       const std::vector<std::string>& extra = {}) {
  std::vector<std::string> o = {set_number("grid.cell_size", cell_size), "mpm.shape_function=" + shape_function};
  o.insert(o.end(), extra.begin(), extra.end());
  const Scenario sc = load_example("cantilever_beam.yaml", o);
  const double x_tip = sc.bodies.at(0).shape.upper[0];
  auto solver = make_solver(sc);
  auto energy = [&] {
    const EnergyTotals e = solver->energies();
    return e.kinetic + e.internal;
  };
  const double E0 = energy();
  CantileverResult r;
  std::vector<double> zeros;
  double t_prev = 0.0, w_prev = 0.0;
  const double end = sc.simulation.end_time;
  while (solver->time() < end * (1.0 - 1e-12)) {
    double dt = solver->stable_dt();
    if (!(dt > 0.0) || !std::isfinite(dt)) throw std::runtime_error("time step collapsed");
    try {
      solver->step(std::min(dt, end - solver->time()));
    } catch (const std::exception& e) {  // a PhysicsError: reported, not thrown (the table goes on)
      r.failure = e.what();
      r.failed_at = solver->time();
      break;
    }
    // Points are reordered (sorted by cell) but none is removed: the mean over x0 > L - h does not
    // depend on their order.
    const FieldStore& pts = solver->points();
    const Vec3* x = pts.view<Vec3>("x");
    const Vec3* X = pts.view<Vec3>("x0");
    double w = 0.0;
    int m = 0;
    for (Index p = 0; p < pts.size(); ++p)
      if (X[p][0] > x_tip - cell_size) {
        w += x[p][1] - X[p][1];
        ++m;
      }
    w /= std::max(m, 1);
    const double t = solver->time();
    if (t_prev > 0.0 && ((w_prev < 0.0 && w >= 0.0) || (w_prev > 0.0 && w <= 0.0)))
      zeros.push_back(t_prev + (t - t_prev) * w_prev / (w_prev - w));
    r.amplitude = std::max(r.amplitude, std::abs(w));
    const double E = energy();
    r.energy_drift = std::max(r.energy_drift, std::abs(E - E0) / E0);
    r.energy_end = (E - E0) / E0;
    t_prev = t;
    w_prev = w;
  }
  r.crossings = static_cast<int>(zeros.size());
  r.period = zeros.size() >= 2 ? 2.0 * (zeros.back() - zeros.front()) / static_cast<double>(zeros.size() - 1) : NAN;
  r.particles = static_cast<long>(solver->points().size());
  r.steps = solver->steps();
  return r;
}

}  // namespace ballista::verification
