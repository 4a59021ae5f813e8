#include "otm/otm_solver.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "points/solver_registry.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTinyMass = 1e-300;

[[noreturn]] void section_error(const Scenario& sc, const std::string& key, const std::string& message) {
  throw DeckError(sc.file, 0, 0, "otm." + key, message);
}

}  // namespace

OtmSolver::OtmSolver(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, Communicator comm)
    : scenario_(sc),
      comm_(comm),
      // Points on each body's lattice (grid.cell_size / particles_per_cell), as for MPM; the support
      // lists cost ~ (number of nodes in reach) x 44 B per point (node index, N, grad N).
      pts_(sc, std::move(materials), SeedLattice{sc.grid, 0, 60.0 * 44.0}, 0.0, "", comm),
      points_(pts_.store()) {
  const ParamValues& P = sc.solver_params;
  if (pts_.pending() > 0)
    section_error(sc, "", "bodies with a later activation (activation_time, activation_stage, rods, jets) are not "
                          "supported by the OTM solver yet: their nodes would have to be seeded on arrival");
  if (sc.simulation.on_particle_exit != "stop")
    section_error(sc, "", "simulation.on_particle_exit: delete is not supported by the OTM solver yet");
  dim_ = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  axisym_ = sc.simulation.dimension == Dimension::Axisymmetric;
  damping_ = sc.simulation.damping;
  penalty_ = P.choices.at("wall_model") == "penalty";
  penalty_factor_ = P.at("penalty");
  sopt_.h = sc.grid.cell_size;
  sopt_.gamma = P.at("gamma");
  sopt_.tolerance = P.at("support_tolerance");
  sopt_.min_support = static_cast<int>(P.at("min_support"));
  sopt_.dim = dim_;
  sopt_.lme.line_search = P.choices.at("line_search") == "on";

  const Index n = points_.size();
  nodes_ = otm::seed_nodes(points_.view<Vec3>("x"), points_.ints("body"), n, sc.grid.lower, sc.grid.cell_size, dim_);
  lambda_.assign(static_cast<size_t>(n), Vec3{});
  refresh_supports();
  // Initial node velocities: the mass-weighted projection of the points' (exact for a body in
  // uniform motion: the shape functions are a partition of unity).
  const auto* v = points_.view<Vec3>("v");
  const auto* mass = points_.real("mass");
  std::vector<Vec3> mom(static_cast<size_t>(nodes_.size()));
  std::vector<double> m(static_cast<size_t>(nodes_.size()), 0.0);
  for (Index p = 0; p < n; ++p)
    for (Index k = sup_.offset[p]; k < sup_.offset[p + 1]; ++k) {
      const Index a = sup_.node[k];
      m[a] += sup_.N[k] * mass[p];
      mom[a] += (sup_.N[k] * mass[p]) * v[p];
    }
  for (Index a = 0; a < nodes_.size(); ++a) {
    nodes_.mass[a] = m[a];
    nodes_.v[a] = m[a] > kTinyMass ? (1.0 / m[a]) * mom[a] : Vec3{};
    momentum0_ += m[a] * nodes_.v[a];
  }
}

const FieldStore* OtmSolver::output_nodes() {
  if (!node_out_.has("x")) {
    node_out_.add_real("x", 3, "m");
    node_out_.add_real("v", 3, "m/s");
    node_out_.add_real("mass", 1, "kg");
    node_out_.add_real("body", 1, "1");
  }
  const Index nn = nodes_.size();
  node_out_.resize(nn);
  auto* x = node_out_.view<Vec3>("x");
  auto* v = node_out_.view<Vec3>("v");
  auto* m = node_out_.real("mass");
  auto* b = node_out_.real("body");
  for (Index a = 0; a < nn; ++a) {
    x[a] = nodes_.x[a];
    v[a] = nodes_.v[a];
    m[a] = nodes_.mass[a];
    b[a] = static_cast<double>(nodes_.body[a]);
  }
  return &node_out_;
}

double OtmSolver::reporting_scale() const { return axisym_ ? 2.0 * std::numbers::pi : 1.0; }

void OtmSolver::begin_stage(int stage, double damping) {
  pts_.begin_stage(stage, time_);
  damping_ = damping;
}

void OtmSolver::refresh_supports() {
  const Index n = points_.size();
  lambda_.resize(static_cast<size_t>(n));
  // Radius scale of each point: the largest principal stretch of F (in the plane in 2D).
  scale_.resize(static_cast<size_t>(n));
  const auto* F = points_.view<Mat3>("F");
  for_each(0, n, [&](Index p) {
    double lo, hi;
    otm::symmetric_extremes(transpose_times(F[p], F[p]), dim_, lo, hi);
    scale_[p] = std::sqrt(std::max(hi, 1.0));
  });
  std::swap(prev_sup_, sup_);
  otm::build_supports(points_.view<Vec3>("x"), points_.ints("body"), n, nodes_.x.data(), nodes_.body.data(),
                      nodes_.size(), sopt_, scale_.data(), prev_sup_.offset.empty() ? nullptr : &prev_sup_,
                      lambda_.data(), sup_);
  retries_ += sup_.retries;
  mean_support_ = sup_.mean_size;
  max_support_ = std::max(max_support_, sup_.max_size);
  max_iterations_ = std::max(max_iterations_, sup_.max_iterations);
  max_condition_ = std::max(max_condition_, sup_.max_condition);
  fallbacks_ += sup_.fallbacks;
  if (sup_.failed < 0) return;
  // The point, its support nodes and the state of the solve (never a NaN weight handed on).
  const Index p = sup_.failed;
  const Index k0 = sup_.offset[p], k1 = sup_.offset[p + 1];
  std::string nodes;
  for (Index k = k0; k < k1 && k < k0 + 8; ++k) {
    const Vec3& x = nodes_.x[sup_.node[k]];
    nodes += fmt::format("{}{} [{:.6g}, {:.6g}, {:.6g}]", k == k0 ? "" : ", ", sup_.node[k], x[0], x[1], x[2]);
  }
  if (k1 - k0 > 8) nodes += ", ...";
  const otm::LmeResult& r = sup_.failed_result;
  pts_.fail(p,
            fmt::format("has no local max-entropy shape functions: the solve for the multiplier failed with "
                        "{} support nodes within {:.4g} m (at least {} needed; otm.gamma = {:g}), residual {:.3g} h "
                        "after {} iterations{}, condition number of the Hessian {:.3g}; support nodes: {}. "
                        "The point has probably left the convex hull of its nodes (otm docs: adaptivity)",
                        k1 - k0, otm::support_radius(sopt_) * std::clamp(scale_[p], 1.0, otm::kMaxScale), sopt_.min_support > 0 ? sopt_.min_support : dim_ + 2,
                        sopt_.gamma, r.residual, r.iterations, r.used_fallback ? " (with the fallback)" : "",
                        r.condition, nodes),
            steps_, time_);
}

void OtmSolver::assemble() {
  // Node-wise gathers over the transposed supports: deterministic for any thread count.
  const Index n = points_.size(), nn = nodes_.size();
  std::vector<Index> start(static_cast<size_t>(nn) + 1, 0);
  for (Index k = 0; k < sup_.offset[n]; ++k) ++start[sup_.node[k] + 1];
  for (Index a = 0; a < nn; ++a) start[a + 1] += start[a];
  std::vector<Index> entry(static_cast<size_t>(start[nn]));
  std::vector<Index> owner(static_cast<size_t>(start[nn]));
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index p = 0; p < n; ++p)
      for (Index k = sup_.offset[p]; k < sup_.offset[p + 1]; ++k) {
        const Index i = fill[sup_.node[k]]++;
        entry[i] = k;
        owner[i] = p;
      }
  }
  const auto* mass = points_.real("mass");
  const auto* vol = points_.real("volume");
  const auto* stress = points_.view<Mat3>("stress");
  const auto* x = points_.view<Vec3>("x");
  const std::vector<Vec3>& fext = loads_.total();
  const bool has_ext = !fext.empty();
  const bool axisym = axisym_;
  for_each(0, nn, [&](Index a) {
    double m = 0.0;
    Vec3 f;
    for (Index i = start[a]; i < start[a + 1]; ++i) {
      const Index k = entry[i], p = owner[i];
      const double N = sup_.N[k];
      const Vec3& g = sup_.dN[k];
      m += N * mass[p];
      // f_a = -V_p sigma_p grad N_a + N_a f_ext,p (seed 003 Algorithm 1 line 9, the weak form 2.7).
      const Mat3& s = stress[p];
      const double V = vol[p];
      for (int r = 0; r < 3; ++r) f[r] -= V * (s(r, 0) * g[0] + s(r, 1) * g[1] + s(r, 2) * g[2]);
      if (axisym) f[0] -= V * s(2, 2) * N / x[p][0];  // hoop term (per-radian volume)
      if (has_ext) f += N * fext[p];
    }
    nodes_.mass[a] = m;
    nodes_.f[a] = f;
  });
}

void OtmSolver::apply_face_conditions(double dt) {
  // Box faces at the nodes: fixed and symmetry faces hold the nodes on them; a wall stops (or, with
  // the penalty, pushes back) a node that would cross it. The kinetic energy a wall takes is booked.
  const GridSpec& g = scenario_.grid;
  const double tol = 1e-9 * g.cell_size;
  double wall_dk = 0.0, reaction = 0.0;
  for (Index a = 0; a < nodes_.size(); ++a) {
    Vec3& v = nodes_.v[a];
    const Vec3& x = nodes_.x[a];
    const double m = nodes_.mass[a];
    for (int ax = 0; ax < dim_; ++ax)
      for (int side = 0; side < 2; ++side) {
        const FaceBC bc = g.faces[2 * ax + side];
        if (bc == FaceBC::Free) continue;
        const double plane = side == 0 ? g.lower[ax] : g.upper[ax];
        const double sign = side == 0 ? 1.0 : -1.0;  // inward normal component
        if (bc == FaceBC::Fixed || bc == FaceBC::Symmetry) {
          if (std::abs(x[ax] - plane) > tol) continue;
          if (bc == FaceBC::Fixed) v = Vec3{};
          else v[ax] = 0.0;
          continue;
        }
        if (penalty_) continue;  // walls by penalty act through the force (assemble)
        // Constraint: the normal displacement into the wall is zero (seed 003 ch. 4).
        const double gap = sign * (x[ax] + dt * v[ax] - plane);  // < 0: would cross
        if (gap >= 0.0) continue;
        const double vn = (plane - x[ax]) / dt;
        // The wall takes the normal kinetic energy the node had at the start of the step: the
        // force of this step did no work on the stopped node (its strain rate, from the constrained
        // velocity, stores none), so what the update added is not lost, only what the node
        // brought in (zero for a node resting on the wall).
        const double v_start = v_start_[a][ax];
        wall_dk += 0.5 * m * (vn * vn - v_start * v_start);
        reaction += sign * m * (vn - v[ax]) / dt;
        v[ax] = vn;
      }
  }
  wall_work_ += wall_dk;
  if (!penalty_) wall_force_ = reaction;
}

double OtmSolver::stable_dt() {
  // The central difference is stable for dt <= 2 / omega_max (Belytschko, Liu & Moran, Nonlinear
  // Finite Elements for Continua and Structures (2000) §6.3). omega_max^2 is bounded by the largest
  // row sum of M^-1 K (Gershgorin), with the tangent stiffness of a point bounded by its P-wave
  // modulus rho c^2: K_ab <= sum_p V_p rho_p c^2 g_a,p g_b,p, g_a,p = |grad N_a(x_p)| (+ N_a / r_p,
  // the hoop strain, in axisymmetric runs). So omega_a^2 <= (1/m_a) sum_p m_p c^2 g_a,p G_p with
  // G_p = sum_b g_b,p, and dt = CFL * 2 / max_a omega_a (CFL 1 is the bound itself). For the
  // lumped linear finite element on a regular 1D mesh this is exactly h / c; for LME it follows
  // the supports as the nodes move with the material (the seed's "conservative Courant condition
  // estimate", Algorithm 1 line 10).
  const Index n = points_.size(), nn = nodes_.size();
  const double c = comm_.max(pts_.max_signal_speed());
  const double max_dt = scenario_.simulation.max_dt > 0.0 ? scenario_.simulation.max_dt : kInf;
  if (!(c > 0.0) || n == 0) return std::min(max_dt, scenario_.simulation.end_time);
  const auto* mass = points_.real("mass");
  const auto* x = points_.view<Vec3>("x");
  std::vector<double> k(static_cast<size_t>(nn), 0.0), m(static_cast<size_t>(nn), 0.0);
  auto g = [&](Index p, Index kk) {
    double v = norm(sup_.dN[kk]);
    if (axisym_) v += sup_.N[kk] / x[p][0];
    return v;
  };
  for (Index p = 0; p < n; ++p) {
    double G = 0.0;
    for (Index kk = sup_.offset[p]; kk < sup_.offset[p + 1]; ++kk) G += g(p, kk);
    for (Index kk = sup_.offset[p]; kk < sup_.offset[p + 1]; ++kk) {
      const Index a = sup_.node[kk];
      k[a] += mass[p] * G * g(p, kk);
      m[a] += sup_.N[kk] * mass[p];
    }
  }
  double w2 = 0.0;
  omega2_.assign(static_cast<size_t>(nn), 0.0);
  for (Index a = 0; a < nn; ++a)
    if (m[a] > kTinyMass) {
      omega2_[a] = k[a] / m[a] * c * c;
      w2 = std::max(w2, omega2_[a]);
    }
  w2 = comm_.max(w2);
  // A penalty wall's spring k_a = penalty m_a omega_a^2 raises a wall node's omega^2 by the
  // factor 1 + penalty.
  const double bound = penalty_ ? 2.0 / std::sqrt(1.0 + penalty_factor_) : 2.0;
  const double dt = w2 > 0.0 ? scenario_.simulation.cfl * bound / std::sqrt(w2) : scenario_.simulation.end_time;
  return std::min(dt, max_dt);
}

void OtmSolver::step(double dt) {
  const Index n = points_.size(), nn = nodes_.size();
  loads_.compute(scenario_, points_, time_);
  assemble();
  // Rigid walls by penalty: a spring k_a = penalty m_a omega_a^2 on how far a node is behind the
  // wall, omega_a^2 the node's Gershgorin bound (stable_dt): as stiff as the material around the
  // node times `penalty`, independent of the time step (stable_dt shortens the step for it).
  double wall_force = 0.0;
  std::vector<Vec3> fpen;
  if (penalty_) {
    fpen.assign(static_cast<size_t>(nn), Vec3{});
    const GridSpec& g = scenario_.grid;
    for (Index a = 0; a < nn; ++a)
      for (int ax = 0; ax < dim_; ++ax)
        for (int side = 0; side < 2; ++side) {
          if (g.faces[2 * ax + side] != FaceBC::Wall) continue;
          const double plane = side == 0 ? g.lower[ax] : g.upper[ax];
          const double sign = side == 0 ? 1.0 : -1.0;
          const double depth = sign * (plane - nodes_.x[a][ax]);  // > 0: behind the wall
          if (depth <= 0.0) continue;
          const double fn = penalty_factor_ * nodes_.mass[a] * omega2_[a] * depth;
          fpen[a][ax] += sign * fn;
          wall_force += sign * fn;
        }
    wall_force_ = wall_force;
  }
  // Central difference with a variable step (Algorithm 1 line 11, l_k = M_k v_k): v_a gains
  // (dt_k + dt_k+1)/2 f_a / m_a; damping -c v (stages) with its work booked (midpoint velocity).
  const double dt_mid = 0.5 * (dt_prev_ + dt);
  v_start_.assign(static_cast<size_t>(nn), Vec3{});
  const double c = damping_;
  double dw[2];
  deterministic_sum<2>(0, nn, [&](Index a, double* o) {
    const double m = nodes_.mass[a];
    if (!(m > kTinyMass)) return;  // a node no point reaches: it keeps its velocity, carries nothing
    Vec3 f = nodes_.f[a];
    if (penalty_) f += fpen[a];
    const Vec3 v0 = nodes_.v[a];
    v_start_[a] = v0;
    const Vec3 acc = (1.0 / m) * f - c * v0;
    nodes_.v[a] = v0 + dt_mid * acc;
    const Vec3 vmid = 0.5 * (v0 + nodes_.v[a]);
    o[0] -= dt_mid * c * m * dot(v0, vmid);
    if (penalty_) o[1] += dt_mid * dot(fpen[a], vmid);
  }, dw);
  damping_work_ += comm_.sum(dw[0]);
  wall_work_ += comm_.sum(dw[1]);
  apply_face_conditions(dt);
  for_each(0, nn, [&](Index a) { nodes_.x[a] += dt * nodes_.v[a]; });

  // Points follow the nodes (Algorithm 1 lines 12-16) with the shape functions of x_p^k.
  auto* x = points_.view<Vec3>("x");
  auto* v = points_.view<Vec3>("v");
  auto* F = points_.view<Mat3>("F");
  auto* L = points_.view<Mat3>("L");
  auto* vol = points_.real("volume");
  const auto* vol0 = points_.real("volume0");
  const std::vector<Vec3>& fext = loads_.total();
  const bool has_ext = !fext.empty();
  std::atomic<Index> bad{n};
  double ew[1];
  deterministic_sum<1>(0, n, [&](Index p, double* o) {
    Vec3 xn, vp;
    Mat3 l;
    for (Index k = sup_.offset[p]; k < sup_.offset[p + 1]; ++k) {
      const Index a = sup_.node[k];
      const double N = sup_.N[k];
      xn += N * nodes_.x[a];
      vp += N * nodes_.v[a];
      const Vec3& g = sup_.dN[k];
      const Vec3& va = nodes_.v[a];
      for (int i = 0; i < dim_; ++i)
        for (int j = 0; j < dim_; ++j) l(i, j) += va[i] * g[j];
    }
    // Axisymmetric hoop stretch r_k+1 / r_k over the step, exactly.
    if (axisym_) l(2, 2) = (xn[0] / x[p][0] - 1.0) / dt;
    if (has_ext) o[0] += dt * dot(fext[p], vp);
    x[p] = xn;
    v[p] = vp;
    L[p] = l;
    // dF = I + dt sum_a v_a (x) grad N_a = sum_a x_a^k+1 (x) grad N_a (line 13, by the first-order
    // consistency of the shape functions); F and V (lines 14-15).
    F[p] = (Mat3::identity() + dt * l) * F[p];
    const double J = det(F[p]);
    vol[p] = vol0[p] * J;
    if (!(J > 0.0) || !all_finite(F[p]) || !all_finite(xn)) {
      Index cur = bad.load();
      while (p < cur && !bad.compare_exchange_weak(cur, p)) {
      }
    }
  }, ew);
  external_work_ += comm_.sum(ew[0]);
  dt_prev_ = dt;
  time_ += dt;
  ++steps_;
  if (const Index p = bad.load(); p < n) pts_.fail(p, "inverted or non-finite deformation gradient (J <= 0 or NaN)", steps_, time_);
  pts_.update_stress(dt, steps_, time_);
  refresh_supports();
}

EnergyTotals OtmSolver::energies() const {
  const double k = reporting_scale();
  EnergyTotals e = pts_.energies(k, external_work_);
  // The nodes carry the motion: kinetic energy and momentum are theirs.
  double s[4];
  deterministic_sum<4>(0, nodes_.size(), [&](Index a, double* o) {
    const double m = nodes_.mass[a];
    const Vec3& v = nodes_.v[a];
    o[0] += 0.5 * m * dot(v, v);
    o[1] += m * v[0];
    o[2] += m * v[1];
    o[3] += m * v[2];
  }, s);
  e.kinetic = k * s[0];
  e.momentum = Vec3{{axisym_ ? 0.0 : k * s[1], k * s[2], k * s[3]}};
  e.damping = k * damping_work_;
  e.contact = k * wall_work_;
  return e;
}

std::string OtmSolver::derived_constants() const {
  return fmt::format(
      "# otm: {} nodes, {} points; beta = gamma / h^2 = {:.6g} 1/m^2; support radius {:.6g} m "
      "({:.3g} h); {:.1f} support nodes per point on average\n",
      nodes_.size(), points_.size(), sopt_.gamma / (sopt_.h * sopt_.h), otm::support_radius(sopt_),
      otm::support_radius(sopt_) / sopt_.h, sup_.mean_size);
}

std::vector<std::string> OtmSolver::history_columns() const { return {"wall_force"}; }

std::vector<double> OtmSolver::history_values() const { return {reporting_scale() * wall_force_}; }

std::vector<std::pair<std::string, double>> OtmSolver::result_values() const {
  const EnergyTotals e = energies();
  const Vec3 p0 = reporting_scale() * momentum0_;
  return {{"node_count", static_cast<double>(nodes_.size())},
          {"support_mean", mean_support_},
          {"support_max", static_cast<double>(max_support_)},
          {"lme_max_iterations", static_cast<double>(max_iterations_)},
          {"lme_max_condition", max_condition_},
          {"lme_fallbacks", static_cast<double>(fallbacks_)},
          {"support_retries", static_cast<double>(retries_)},
          {"lme_failures", 0.0},  // a failed solve stops the run
          {"momentum_change_x", axisym_ ? 0.0 : e.momentum[0] - p0[0]},
          {"momentum_change_y", e.momentum[1] - p0[1]},
          {"momentum_change_z", e.momentum[2] - p0[2]}};
}

namespace {

std::unique_ptr<Solver> make_otm(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials) {
  return std::make_unique<OtmSolver>(sc, std::move(materials));
}


std::vector<ParamSpec> otm_params() {
  ParamSpec gamma{"gamma", "1",
                  "LME locality gamma = beta h^2 (h = grid.cell_size, the nodal spacing; seed 003 Fig. 5-5): larger "
                  "is more local (the finite-element limit), smaller smoother",
                  false, 1.8, 0.0, 50.0, true};
  ParamSpec tol{"support_tolerance", "1",
                "weight cut-off of the support radius h sqrt(-ln(tol)/gamma)", false, 1e-4, 0.0, 0.1, true};
  ParamSpec minsup{"min_support", "1", "fewest support nodes of a point (0: dimension + 2)", false, 0, 0, 1000};
  minsup.integer = true;
  const ParamSpec wall = word_param("wall_model",
                              "rigid walls (faces marked wall): constraint (no normal displacement into the wall) or "
                              "penalty (a spring on the crossing; seed 003 ch. 4)",
                              {"constraint", "penalty"});
  ParamSpec pen{"penalty", "1",
                "penalty walls: spring k_a = penalty m_a omega_a^2 (the node's own stiffness bound times this)", false,
                1.0, 0.0, 100.0, true};
  const ParamSpec ls = word_param("line_search", "backtracking line search in the LME Newton solve (seed 003 Fig. 5-5)",
                            {"on", "off"});
  return {gamma, tol, minsup, wall, pen, ls};
}

}  // namespace

}  // namespace ballista

BALLISTA_REGISTER_SOLVER(ballista::SolverFactory{
    "otm",
    "optimal transportation meshfree method with local max-entropy shape functions (Li, Habbal & Ortiz 2010; "
    "seed 003)",
    {"3d", "plane_strain", "axisymmetric"},
    "otm",
    ballista::otm_params(),
    &ballista::make_otm})
