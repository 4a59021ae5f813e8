#include "driver/point_driver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <utility>

#include "core/field_store.hpp"
#include "core/point_fields.hpp"
#include "core/polar.hpp"
#include "geometry/seeding.hpp"

namespace ballista {

const char* voigt_name(int k) {
  static const char* const kNames[6] = {"11", "22", "33", "23", "13", "12"};
  return k >= 0 && k < 6 ? kNames[k] : "?";
}

namespace {

/// MaterialBatch::plastic_work: the plastic dissipation of the current step (J/m^3).
constexpr FieldKey<double> kStepWork{"plastic_work_step"};
/// Absolute floor of the stress-control tolerance per unit stiffness (see Driver::solve_step).
constexpr double kStressNoise = 1e-14;

std::string num(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

std::string mat_text(const Mat3& A) {
  std::string s = "[";
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s += num(A(i, j)) + (j < 2 ? " " : i < 2 ? "; " : "]");
  return s;
}

/// exp of a symmetric matrix: exact std::exp on a diagonal one; otherwise scaling and squaring
/// of the Taylor series (Moler & Van Loan, SIAM Review 45 (2003) 3, "method 3"): with
/// |A/2^s| <= 1/2 the series truncated after 20 terms is accurate to round-off (1/2^21/21! << 1e-16).
Mat3 exp_sym(const Mat3& A) {
  if (A(0, 1) == 0.0 && A(0, 2) == 0.0 && A(1, 2) == 0.0 && A(1, 0) == 0.0 && A(2, 0) == 0.0 && A(2, 1) == 0.0)
    return Mat3::diag(std::exp(A(0, 0)), std::exp(A(1, 1)), std::exp(A(2, 2)));
  const double n = frobenius(A);
  int s = 0;
  if (n > 0.5) s = static_cast<int>(std::ceil(std::log2(n / 0.5)));
  const Mat3 X = std::ldexp(1.0, -s) * A;
  Mat3 term = Mat3::identity(), sum = Mat3::identity();
  for (int k = 1; k <= 20; ++k) {
    term = (1.0 / k) * (term * X);
    sum += term;
  }
  for (int k = 0; k < s; ++k) sum = sum * sum;
  return sym(sum);
}

/// Solves the m x m system J x = b (row-major J) by Gaussian elimination with partial pivoting;
/// false if a pivot is below 1e-14 of the largest entry (singular to working precision).
bool solve_dense(int m, double* J, double* b, double* x) {
  double jmax = 0.0;
  for (int k = 0; k < m * m; ++k) jmax = std::max(jmax, std::abs(J[k]));
  if (!(jmax > 0.0)) return false;
  for (int c = 0; c < m; ++c) {
    int piv = c;
    for (int r = c + 1; r < m; ++r)
      if (std::abs(J[r * m + c]) > std::abs(J[piv * m + c])) piv = r;
    if (!(std::abs(J[piv * m + c]) > 1e-14 * jmax)) return false;
    if (piv != c) {
      for (int k = 0; k < m; ++k) std::swap(J[c * m + k], J[piv * m + k]);
      std::swap(b[c], b[piv]);
    }
    for (int r = c + 1; r < m; ++r) {
      const double f = J[r * m + c] / J[c * m + c];
      for (int k = c; k < m; ++k) J[r * m + k] -= f * J[c * m + k];
      b[r] -= f * b[c];
    }
  }
  for (int r = m - 1; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < m; ++k) s -= J[r * m + k] * x[k];
    x[r] = s / J[r * m + r];
  }
  return true;
}

class Driver {
 public:
  Driver(const Material& material, const DriveProgram& program) : mat_(material), prog_(program) {
    for (const auto& s : mat_.state_fields()) result_.state_names.push_back(s.name);
    // The solvers' point fields and the model's state (thesis §4.2.1: the same update path).
    declare_point_fields(base_);
    base_.declare(kStepWork, "J/m^3", false);
    mat_.declare_fields(base_);
    base_.resize(1);
  }

  DriveResult run() {
    const bool has_table = !prog_.table.empty(), has_legs = !prog_.legs.empty();
    if (!has_table && !has_legs) throw Error("drive program: no F-table rows and no legs (nothing to drive)");
    if (has_table && has_legs) throw Error("drive program: give either an F-table or legs, not both");
    if (prog_.record_every < 1)
      throw Error("drive program: record_every must be >= 1, got " + std::to_string(prog_.record_every));
    if (has_table)
      validate_table();
    else
      validate_legs();
    try {
      if (has_table)
        run_table();
      else
        run_legs();
    } catch (const PhysicsError& e) {
      if (!error_) throw;
      *error_ = e.what();
      result_.steps = step_;
      // The last record is the failing step as the model left it (non-finite values included, or
      // the last trial of a stress control that did not converge).
      if (failed_store_) {
        ++step_;
        t_ = failed_t_;
        record(*failed_store_, -1, true);
      }
    }
    return std::move(result_);
  }

  /// Collect a PhysicsError into `error` instead of throwing it.
  void catch_physics(std::string* error) { error_ = error; }

 private:
  // ---- the point ----------------------------------------------------------------------------
  void init(const Mat3& F0, double t0) {
    base_.view(kDeformationGradient)[0] = F0;
    base_.view(kRotation)[0] = polar_rotation(F0);
    base_.view(kStress)[0] = mat_.initial_stress(F0);
    base_.real(kReferenceVolume)[0] = 1.0;  // 1 m^3: energies are then per m^3 of reference volume
    base_.real(kVolume)[0] = det(F0);
    base_.real(kMass)[0] = mat_.density();
    t_ = t0;
    record(base_, 0, true);
  }

  /// One material update of the point in `s` to F_new over dt, through a MaterialBatch filled as
  /// MpmSolver::update_stress fills it; L from thesis eq. 4.10. Returns false if the new stress or
  /// F is not finite.
  bool advance(FieldStore& s, const Mat3& F_new, double dt) const {
    Mat3* F = s.view(kDeformationGradient);
    Mat3* L = s.view(kVelocityGradient);
    // L = (F_{n+1} F_n^{-1} - I)/dt (thesis seed 000 eq. 4.10).
    L[0] = (1.0 / dt) * (F_new * inverse(F[0]) - Mat3::identity());
    F[0] = F_new;
    s.real(kVolume)[0] = s.real(kReferenceVolume)[0] * det(F_new);
    static const Index kPoint[1] = {0};
    MaterialBatch b = make_batch(s, kPoint, 1, dt, true);  // as the solvers' (points/point_set.cpp)
    b.plastic_work = s.real(kStepWork);
    b.time = t_ + dt;  // t_{n+1} (an explosive stays unreacted here: no program burn in a drive)
    mat_.update(b);
    // Garbage is a failure, never a completed drive (a compressive leg can underflow J to 0 and
    // would otherwise complete): the stress, F, J > 0 and every state variable must hold.
    if (!all_finite(b.stress[0]) || !all_finite(F[0]) || !(det(F[0]) > 0.0)) return false;
    for (const auto& n : result_.state_names)
      if (!std::isfinite(s.real(n)[0])) return false;
    return true;
  }

  /// Appends a record of `s` at t_ if this step is due (or forced).
  void record(const FieldStore& s, int iterations, bool force) {
    if (!force && step_ % prog_.record_every != 0) return;
    DriveRecord r;
    r.t = t_;
    r.step = step_;
    r.F = s.view(kDeformationGradient)[0];
    r.R = s.view(kRotation)[0];
    r.sigma = s.view(kStress)[0];
    r.sigma_bar = unrotate_sym(r.R, r.sigma);  // R^T sigma R
    for (const auto& n : result_.state_names) r.state.push_back(s.real(n)[0]);
    r.plastic_work = s.real(kStepWork)[0];
    r.internal_energy = s.real(kInternalEnergy)[0];
    r.plastic_work_total = s.real(kPlasticWork)[0];
    r.iterations = iterations;
    result_.records.push_back(std::move(r));
  }

  /// What an error message shows of the state at t_n (copied before each update: cheap).
  struct Snapshot {
    Mat3 F, stress;
    std::vector<double> state;
  };
  void snapshot(const FieldStore& s, Snapshot& out) const {
    out.F = s.view(kDeformationGradient)[0];
    out.stress = s.view(kStress)[0];
    out.state.resize(result_.state_names.size());
    for (size_t k = 0; k < out.state.size(); ++k) out.state[k] = s.real(result_.state_names[k])[0];
  }
  std::string state_text(const std::vector<double>& st) const {
    std::string out;
    for (size_t k = 0; k < st.size(); ++k)
      out += (out.empty() ? "" : ", ") + result_.state_names[k] + " = " + num(st[k]);
    return out.empty() ? "(no state fields)" : out;
  }

  /// The PhysicsError for a non-finite update from `before` (state at t_n) to `after`.
  [[noreturn]] void fail_nonfinite(const FieldStore& before_store, const FieldStore& after_store, double t_new,
                                   const std::string& where) {
    failed_store_ = &after_store;
    failed_t_ = t_new;
    Snapshot before, after;
    snapshot(before_store, before);
    snapshot(after_store, after);
    fail_nonfinite(before, after, t_new, where);
  }
  [[noreturn]] void fail_nonfinite(const Snapshot& before, const FieldStore& after_store, double t_new,
                                   const std::string& where) {
    failed_store_ = &after_store;
    failed_t_ = t_new;
    Snapshot after;
    snapshot(after_store, after);
    fail_nonfinite(before, after, t_new, where);
  }
  [[noreturn]] void fail_nonfinite(const Snapshot& before, const Snapshot& after, double t_new,
                                   const std::string& where) const {
    std::ostringstream os;
    os << "drive: non-finite stress, F or state, or J <= 0, after the material update (" << mat_.name()
       << ", model " << mat_.model()
       << ") at step " << step_ + 1 << " (t = " << num(t_new) << " s" << where << ")\n"
       << "  F_n     = " << mat_text(before.F) << ", J = " << num(det(before.F))
       << "\n  F_n+1   = " << mat_text(after.F) << ", J = " << num(det(after.F))
       << "\n  stress_n   = " << mat_text(before.stress) << " Pa"
       << "\n  stress_n+1 = " << mat_text(after.stress) << " Pa"
       << "\n  state_n:   " << state_text(before.state) << "\n  state_n+1: " << state_text(after.state);
    throw PhysicsError(os.str());
  }

  // ---- F-table ------------------------------------------------------------------------------
  void validate_table() const {
    const auto& rows = prog_.table;
    if (rows.size() < 2)
      throw Error("drive program: an F-table needs at least 2 rows (the initial state and one more), got " +
                  std::to_string(rows.size()));
    if (prog_.substeps < 1) throw Error("drive program: substeps must be >= 1, got " + std::to_string(prog_.substeps));
    for (size_t k = 0; k < rows.size(); ++k) {
      const FTableRow& r = rows[k];
      const std::string row = "drive program: F-table row " + std::to_string(k) + " (t = " + num(r.t) + "): ";
      if (!std::isfinite(r.t) || !all_finite(r.F) || !std::isfinite(r.angle_deg) || !all_finite(r.axis))
        throw Error(row + "non-finite entry");
      if (k > 0 && !(r.t > rows[k - 1].t))
        throw Error(row + "times must increase strictly; " + num(r.t) + " follows " + num(rows[k - 1].t));
      // J = det F is the volume ratio: a row below 1e-6 (a millionth of the volume; no material
      // model is defined there, metals under the strongest shocks stay above 0.3) is a typing
      // slip or garbage, not a test (the fuzzer's F33 = 1e-300 ran to "success").
      if (!(det(r.F) >= 1e-6))
        throw Error(row + "det F = " + num(det(r.F)) + " (must be >= 1e-6: a volume ratio); F = " + mat_text(r.F));
      if (k == 0 && r.angle_deg != 0.0)
        throw Error(row +
                    "the first row is the initial state: its rotation angle must be 0 (a rotation "
                    "accumulates over the row that ends at its time), got " +
                    num(r.angle_deg) + " deg");
      if (r.angle_deg != 0.0 && !(norm(r.axis) > 0.0))
        throw Error(row + "rotation of " + num(r.angle_deg) + " deg about a zero axis");
    }
  }

  void run_table() {
    const auto& rows = prog_.table;
    const int S = prog_.substeps;
    init(rows[0].F, rows[0].t);
    Mat3 Q_prev = Mat3::identity();  // superimposed rotation at the end of the previous row
    bool rotated = false;
    for (size_t k = 1; k < rows.size(); ++k) {
      const FTableRow& a = rows[k - 1];
      const FTableRow& b = rows[k];
      const double theta = b.angle_deg * std::numbers::pi / 180.0;
      const Vec3 axis = theta != 0.0 ? (1.0 / norm(b.axis)) * b.axis : Vec3{{0.0, 0.0, 1.0}};
      rotated = rotated || theta != 0.0;
      for (int j = 1; j <= S; ++j) {
        const double tau = static_cast<double>(j) / S;
        // The row's end is hit exactly (no interpolation round-off in its F or t).
        const double t_new = j == S ? b.t : a.t + tau * (b.t - a.t);
        Mat3 F = j == S ? b.F : a.F + tau * (b.F - a.F);
        // Q(tau) = Rot(a_k, tau theta_k) Q_{k-1} (thesis §4.2.1, Euler-Rodrigues formula).
        if (rotated) F = (rotation_about(axis, tau * theta) * Q_prev) * F;
        const double dt = t_new - t_;
        if (!all_finite(F) || !(det(F) > 0.0))
          throw Error("drive program: the interpolated F at step " + std::to_string(step_ + 1) + " (t = " + num(t_new) +
                      " s, between rows " + std::to_string(k - 1) + " and " + std::to_string(k) +
                      ") has det F = " + num(det(F)) + " (must be > 0); F = " + mat_text(F) +
                      " (use more rows: F is interpolated linearly)");
        if (!(dt > 0.0))
          throw Error("drive program: time step " + num(dt) + " s at step " + std::to_string(step_ + 1) + " (rows " +
                      std::to_string(k - 1) + ", " + std::to_string(k) + " too close for the substeps)");
        snapshot(base_, prev_);  // kept only for the error message
        if (!advance(base_, F, dt))
          fail_nonfinite(prev_, base_, t_new, ", F-table rows " + std::to_string(k - 1) + "-" + std::to_string(k));
        ++step_;
        t_ = t_new;
        record(base_, 0, j == S);
      }
      if (rotated) Q_prev = rotation_about(axis, theta) * Q_prev;
    }
    result_.steps = step_;
  }

  // ---- legs ---------------------------------------------------------------------------------
  void validate_legs() const {
    for (size_t l = 0; l < prog_.legs.size(); ++l) {
      const DriveLeg& g = prog_.legs[l];
      const std::string leg = "drive program: leg " + std::to_string(l) + ": ";
      if (!(g.duration > 0.0) || !std::isfinite(g.duration))
        throw Error(leg + "duration must be > 0 s, got " + num(g.duration));
      if (g.steps < 1) throw Error(leg + "steps must be >= 1, got " + std::to_string(g.steps));
      for (int k = 0; k < 6; ++k)
        if (!std::isfinite(g.value[k])) throw Error(leg + "non-finite value for component " + voigt_name(k));
    }
    if (prog_.max_iterations < 1) throw Error("drive program: max_iterations must be >= 1");
    if (!(prog_.stress_tolerance > 0.0)) throw Error("drive program: stress_tolerance must be > 0");
  }

  /// Spatial symmetric increment from the 6 components (tensor shear strains).
  static Mat3 increment(const double* e6) {
    Mat3 E;
    for (int k = 0; k < 6; ++k) {
      E(kVoigtI[k], kVoigtJ[k]) = e6[k];
      E(kVoigtJ[k], kVoigtI[k]) = e6[k];
    }
    return E;
  }

  /// Trial update of a copy of base_ into `s` with increment e6; residuals of the held components
  /// in r (size m). False if the update is not finite.
  bool evaluate(FieldStore& s, const double* e6, double dt, int m, const int* held, const double* target,
                double* r) const {
    s = base_;  // same fields: copies values into the existing buffers
    const Mat3 F_new = exp_sym(increment(e6)) * base_.view(kDeformationGradient)[0];
    if (!advance(s, F_new, dt)) return false;
    const Mat3& sig = s.view(kStress)[0];
    for (int c = 0; c < m; ++c) r[c] = sig(kVoigtI[held[c]], kVoigtJ[held[c]]) - target[c];
    return true;
  }

  static double max_abs(int m, const double* r) {
    double x = 0.0;
    for (int c = 0; c < m; ++c) x = std::max(x, std::abs(r[c]));
    return x;
  }

  void run_legs() {
    init(Mat3::identity(), 0.0);
    for (size_t l = 0; l < prog_.legs.size(); ++l) {
      const DriveLeg& g = prog_.legs[l];
      const double dt = g.duration / g.steps;
      int held[6], m = 0;
      double e6[6], start[6] = {};
      const Mat3 sig0 = base_.view(kStress)[0];
      for (int k = 0; k < 6; ++k) {
        e6[k] = g.stress_controlled[k] ? 0.0 : g.value[k] / g.steps;
        if (g.stress_controlled[k]) {
          start[m] = sig0(kVoigtI[k], kVoigtJ[k]);
          held[m++] = k;
        }
      }
      const double t_leg = t_;
      for (int n = 1; n <= g.steps; ++n) {
        const double t_new = n == g.steps ? t_leg + g.duration : t_leg + n * dt;
        int iterations = 0;
        if (m == 0) {
          snapshot(base_, prev_);
          if (!advance(base_, exp_sym(increment(e6)) * base_.view(kDeformationGradient)[0], dt))
            fail_nonfinite(prev_, base_, t_new, ", leg " + std::to_string(l));
        } else {
          // Held components follow target = start + (value - start) n/N (linear in time).
          double target[6];
          const double frac = static_cast<double>(n) / g.steps;
          for (int c = 0; c < m; ++c) target[c] = start[c] + (g.value[held[c]] - start[c]) * frac;
          iterations = solve_step(l, n, e6, dt, t_new, m, held, target);
          std::swap(base_, trial_);  // commit the converged trial update (no extra update)
        }
        ++step_;
        t_ = t_new;
        record(base_, iterations, n == g.steps);
        result_.max_iterations = std::max(result_.max_iterations, iterations);
      }
    }
    result_.steps = step_;
  }

  /// Newton's method on the held components of the increment e6 (initial guess: e6 as given,
  /// i.e. the previous step's solution). Leaves the converged update in trial_; returns the number
  /// of Newton iterations.
  ///
  /// Tolerance: the update is a few dozen flops on stresses of size |sigma|, so its relative
  /// round-off is ~1e-15; the default 1e-10 relative to max(|sigma_{n+1}|, |targets|) sits 5
  /// orders above that (reached reliably) and well below anything a test resolves (a lateral
  /// stress of 1e-10 |sigma| changes strains by 1e-10 |sigma|/E). Near zero stress the floor is
  /// absolute: eq. 4.10 forms the strain increment as F_{n+1} F_n^-1 - I, whose entries carry an
  /// absolute round-off ~1e-16, i.e. a stress noise ~1e-16 x the stiffness (2e-5 Pa for steel);
  /// residuals below kStressNoise = 1e-14 x the largest Jacobian entry (100x that noise) count as
  /// converged.
  int solve_step(size_t leg, int n, double* e6, double dt, double t_new, int m, const int* held, const double* target) {
    const double tol = prog_.stress_tolerance;
    double strain_scale = 1e-6;  // forward-difference step: 1e-7 of the increments' size
    for (int k = 0; k < 6; ++k) strain_scale = std::max(strain_scale, std::abs(e6[k]));
    double r[6], rp[6], J[36], delta[6], rhs[6];
    auto where = [&] {
      return ", leg " + std::to_string(leg) + " step " + std::to_string(n) + " of " +
             std::to_string(prog_.legs[leg].steps);
    };
    auto converged = [&](const double* res) {
      const double scale = std::max(frobenius(trial_.view(kStress)[0]), max_abs(m, target));
      return max_abs(m, res) <= std::max(tol * scale, kStressNoise * jac_scale_);
    };
    if (!evaluate(trial_, e6, dt, m, held, target, r)) fail_nonfinite(base_, trial_, t_new, where());
    for (int it = 0; it <= prog_.max_iterations; ++it) {
      if (converged(r)) return it;
      if (it == prog_.max_iterations) break;
      // Forward-difference Jacobian d r / d e_held.
      const double h = 1e-7 * strain_scale;
      for (int c = 0; c < m; ++c) {
        double ep[6];
        std::copy(e6, e6 + 6, ep);
        ep[held[c]] += h;
        if (!evaluate(probe_, ep, dt, m, held, target, rp)) fail_nonfinite(base_, probe_, t_new, where());
        for (int q = 0; q < m; ++q) J[q * m + c] = (rp[q] - r[q]) / h;
      }
      jac_scale_ = 0.0;
      for (int q = 0; q < m * m; ++q) jac_scale_ = std::max(jac_scale_, std::abs(J[q]));
      for (int c = 0; c < m; ++c) rhs[c] = -r[c];
      failed_store_ = &trial_;
      failed_t_ = t_new;
      if (!solve_dense(m, J, rhs, delta))
        throw PhysicsError("drive: stress control has a singular Jacobian at step " + std::to_string(step_ + 1) +
                           " (t = " + num(t_new) + " s" + where() +
                           "): the held stress components do not respond independently to their strains "
                           "(e.g. all components held on a perfectly plastic yield surface)");
      // Backtracking line search on max |r|.
      const double r0 = max_abs(m, r);
      double lambda = 1.0;
      bool accepted = false;
      for (int ls = 0; ls < 30 && !accepted; ++ls, lambda *= 0.5) {
        double e_try[6];
        std::copy(e6, e6 + 6, e_try);
        for (int c = 0; c < m; ++c) e_try[held[c]] += lambda * delta[c];
        if (evaluate(cand_, e_try, dt, m, held, target, rp) && max_abs(m, rp) < r0) {
          std::copy(e_try, e_try + 6, e6);
          std::copy(rp, rp + m, r);
          std::swap(trial_, cand_);
          accepted = true;
        }
      }
      if (!accepted) {
        if (converged(r)) return it + 1;
        break;
      }
      for (int c = 0; c < m; ++c) strain_scale = std::max(strain_scale, std::abs(e6[held[c]]));
    }
    std::ostringstream os;
    os << "drive: stress control did not converge at step " << step_ + 1 << " (t = " << num(t_new) << " s" << where()
       << ") after " << prog_.max_iterations << " iterations: residuals";
    for (int c = 0; c < m; ++c) os << " sigma" << voigt_name(held[c]) << " - target = " << num(r[c]) << " Pa";
    os << " (tolerance " << num(tol) << " relative to the stress scale; raise drive.stress_tolerance or use "
       << "more steps)\n  F_n = " << mat_text(base_.view(kDeformationGradient)[0])
       << "\n  stress_n = " << mat_text(base_.view(kStress)[0]) << " Pa\n  state_n: ";
    Snapshot now;
    snapshot(base_, now);
    os << state_text(now.state);
    throw PhysicsError(os.str());
  }

  const Material& mat_;
  const DriveProgram& prog_;
  DriveResult result_;
  FieldStore base_;                  ///< the point at t_n (committed state)
  FieldStore trial_, cand_, probe_;  ///< copies of the point for trial updates (stress control)
  Snapshot prev_;                    ///< the point at t_n, for error messages
  long step_ = 0;
  double t_ = 0.0;
  double jac_scale_ = 0.0;                    ///< largest entry of the latest stress-control Jacobian, Pa
  std::string* error_ = nullptr;              ///< where a PhysicsError goes instead of propagating
  const FieldStore* failed_store_ = nullptr;  ///< the point as the failing step left it
  double failed_t_ = 0.0;                     ///< time of the failing step
};

}  // namespace

DriveResult drive_point(const Material& material, const DriveProgram& program) {
  Driver d(material, program);
  return d.run();
}

DriveResult drive_point(const Material& material, const DriveProgram& program, std::string& error) {
  error.clear();
  Driver d(material, program);
  d.catch_physics(&error);
  return d.run();
}

size_t record_nearest(const DriveResult& result, double t) {
  size_t best = 0;
  for (size_t k = 0; k < result.records.size(); ++k)
    if (std::abs(result.records[k].t - t) < std::abs(result.records[best].t - t)) best = k;
  return best;
}

}  // namespace ballista
