#include "otm/otm_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "core/agreed_failure.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/phase_timer.hpp"
#include "core/point_fields.hpp"
#include "geometry/element_seeding.hpp"
#include "materials/failure.hpp"
#include "otm/otm_contact.hpp"
#include "points/cell_bins.hpp"
#include "points/rcb_partition.hpp"
#include "points/solver_registry.hpp"
#include "scenario/material_model.hpp"

namespace ballista {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kTinyMass = 1e-300;
/// A node lighter than this share of the lightest point's mass is carried by the points
/// (OtmSolver::light_nodes). Such a node is about two node spacings or more from every point (the
/// LME weight's factor exp(-gamma d^2 / h^2) is 7e-4 at d = 2h for gamma = 1.8); no node of a
/// freshly seeded body is that light. On the 3D lattice Taylor bar at 0.8 mm, a share of 1e-6 still
/// left nodes between 1e-6 and 1e-3 at 1.4 times the impact speed; with 1e-3 none is faster than
/// the material around it (docs/validation.md).
constexpr double kLightNodeShare = 1e-3;
/// Per point: the node set it belongs to (its body, or 0 for all with otm.nodes: shared) (1).
constexpr FieldKey<std::int64_t> kNodeGroup{"node_group"};
/// Per output node: the body of its node set, as a real like every node dataset (1).
constexpr FieldKey<double> kNodeBody{"body"};

[[noreturn]] void section_error(const Scenario& sc, const std::string& key, const std::string& message) {
  throw_solver_param_error(sc, "otm", key, message);  // at the key's line
}

/// Storage per point of its supports, this build's and the last one's (node index, N, grad N:
/// 44 B per node): the nodes of the lattice within the support radius h sqrt(-ln(tol)/gamma), at
/// least otm.min_support, for the memory estimate (the radius grows with the points' stretch).
double support_bytes_per_point(const Scenario& sc) {
  const OtmParams P = read_otm_params(sc.solver_params);
  const double rho = std::sqrt(-std::log(P.support_tolerance) / P.gamma);  // in node spacings
  const bool three_d = sc.simulation.dimension == Dimension::ThreeD;
  const double nodes = three_d ? 4.0 / 3.0 * std::numbers::pi * rho * rho * rho : std::numbers::pi * rho * rho;
  return 2.0 * 44.0 * std::max({nodes, static_cast<double>(P.min_support), three_d ? 5.0 : 4.0});
}

/// Several ranks: every rank's points, `width` reals each (rows), with their ids and node groups,
/// in id order (the serial run's point order, which sums over points follow).
struct IdOrdered {
  std::vector<double> rows;
  std::vector<std::int64_t> id, group;
};
IdOrdered gather_in_id_order(const Communicator& comm, const std::vector<double>& rows, std::size_t width,
                             const std::int64_t* id, const std::int64_t* group, Index n) {
  std::vector<std::int64_t> ig;
  for (Index p = 0; p < n; ++p) ig.insert(ig.end(), {id[p], group[p]});
  std::vector<int> counts;
  const std::vector<double> all = comm.all_gather_reals(rows, counts);
  ig = comm.all_gather(ig, counts);
  const std::size_t m = ig.size() / 2;
  std::vector<std::size_t> order(m);
  for (std::size_t i = 0; i < m; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ig[2 * a] < ig[2 * b]; });
  IdOrdered out;
  out.rows.resize(m * width);
  out.id.resize(m);
  out.group.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = order[k];
    std::copy(all.begin() + static_cast<std::ptrdiff_t>(width * i),
              all.begin() + static_cast<std::ptrdiff_t>(width * (i + 1)),
              out.rows.begin() + static_cast<std::ptrdiff_t>(width * k));
    out.id[k] = ig[2 * i];
    out.group[k] = ig[2 * i + 1];
  }
  return out;
}

/// Several ranks: every rank's points' positions and node groups, in rank order (the nodes a
/// set of points makes do not depend on their order: otm::seed_nodes sorts them).
void gather_points(const Communicator& comm, std::vector<Vec3>& x, std::vector<std::int64_t>& group) {
  if (!comm.distributed()) return;
  std::vector<double> flat;
  flat.reserve(3 * x.size());
  for (const Vec3& v : x) flat.insert(flat.end(), {v[0], v[1], v[2]});
  std::vector<int> counts;
  flat = comm.all_gather_reals(flat, counts);
  group = comm.all_gather(group, counts);
  x.resize(group.size());
  for (std::size_t i = 0; i < x.size(); ++i) x[i] = Vec3{{flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]}};
}

/// g_a,p of the stable step's bound (stable_dt): |grad N_a(x_p)|, plus the hoop strain's N_a / r_p
/// where `hoop`.
double coupling(const otm::Supports& sup, Index k, const Vec3& xp, bool hoop) {
  double v = norm(sup.dN[k]);
  if (hoop) v += sup.N[k] / xp[0];
  return v;
}

}  // namespace

OtmSolver::OtmSolver(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials, Communicator comm)
    : scenario_(sc),
      comm_(comm),
      // Points on each body's lattice (grid.cell_size / particles_per_cell), as for MPM, with their
      // support lists.
      pts_(sc, std::move(materials), SeedLattice{sc.grid, 0, support_bytes_per_point(sc)}, 0.0, "", comm),
      points_(pts_.store()) {
  const OtmParams P = read_otm_params(sc.solver_params);
  if (pts_.pending() > 0 && P.shared_nodes)
    section_error(sc, "nodes", "a body with a later activation (activation_time, activation_stage, rods, jets) gets "
                               "its own nodes when it arrives; it cannot join a shared node set (use otm.nodes: "
                               "per_body with contact: pinball)");
  delete_exits_ = sc.simulation.on_particle_exit == "delete";
  dim_ = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  axisym_ = sc.simulation.dimension == Dimension::Axisymmetric;
  damping_ = sc.simulation.damping;
  penalty_ = P.penalty_walls;
  penalty_factor_ = P.penalty;
  contact_ = P.contact;
  contact_penalty_ = P.contact_penalty;
  if (contact_ && P.shared_nodes)
    section_error(sc, "contact", "pinball contact acts between bodies with their own nodes; with otm.nodes: shared "
                                 "the bodies are already tied where they touch (choose one)");
  sopt_.h = sc.grid.cell_size;
  sopt_.gamma = P.gamma;
  sopt_.tolerance = P.support_tolerance;
  sopt_.min_support = P.min_support;
  sopt_.dim = dim_;
  sopt_.lme.line_search = P.line_search;
  adapt_.enabled = P.adaptivity;
  adapt_.split_stretch = P.split_stretch;
  adapt_.node_gap = P.node_gap;
  adapt_.node_crowding = P.node_crowding;
  adapt_.max_condition = P.max_condition;
  // What a split interpolates: the stress and every model's continuous internal variables.
  split_state_.interpolate = P.interpolate_split_state;
  split_state_.fields = {kStress.name()};
  for (const auto& m : pts_.materials())
    for (const StateFieldSpec& f : m->state_fields())
      if (f.continuous && std::find(split_state_.fields.begin(), split_state_.fields.end(), f.name) ==
                              split_state_.fields.end())
        split_state_.fields.push_back(f.name);
  fbar_on_ = P.fbar;
  symmetric_bound_ = P.symmetric_step_bound;

  const Index n = points_.size();
  if (adapt_.enabled) {
    // The extent tensor of each point's cell (s0 I at seeding) and the ids the splits continue.
    for (const BodySpec& b : sc.bodies) spacing_.push_back(sc.grid.cell_size / b.particles_per_cell);
    pts_.declare(otm::kExtent, "m", false);  // also on the bodies not active yet
    seed_extents(0, n);
    Fr_.assign(static_cast<size_t>(n), Mat3::identity());
  }
  // Node groups: each body its own nodes (bodies do not interact), or one node set over every body
  // (otm.nodes: shared; bodies then move together where they touch, as MPM's single_field).
  pts_.declare(kNodeGroup, "1", false);
  {
    auto* group = points_.ints(kNodeGroup);
    const auto* body = points_.ints(kBodyIndex);
    const bool shared = P.shared_nodes;
    // Products that act on nothing would "succeed" with the other bodies untouched.
    if (first_material_of_model(sc, "explosive") && sc.bodies.size() > 1 && !shared)
      section_error(sc, "nodes", "an explosive with other bodies needs otm.nodes: shared (with a node set per body "
                                 "the products would push nothing: the pinball contact is for solids)");
    for (Index p = 0; p < n; ++p) group[p] = shared ? 0 : body[p];
  }
  // Every rank seeded every body, so every rank makes every node; then it keeps its share of the
  // points (several ranks).
  nodes_ = initial_nodes(sc, P);
  seeded_points_ = n;
  keep_region_share();
  const Index own = points_.size();
  if (adapt_.enabled) Fr_.resize(static_cast<size_t>(own));
  lambda_.assign(static_cast<size_t>(own), Vec3{});
  refresh_supports();
  project_node_velocities(0, own, 0);
  reduce_support_statistics();
}

bool OtmSolver::pending_anywhere() const { return comm_.any(pts_.pending() > 0); }

void OtmSolver::reduce_support_statistics() {
  SupportTotals& t = support_totals_;
  if (!comm_.distributed()) {
    t = {mean_support_, max_condition_, max_support_, max_iterations_, fallbacks_, retries_};
    return;
  }
  const double own = static_cast<double>(points_.size());
  double s[4] = {mean_support_ * own, own, static_cast<double>(fallbacks_), static_cast<double>(retries_)};
  comm_.sum(s, 4);
  t.mean = s[1] > 0.0 ? s[0] / s[1] : 0.0;
  t.fallbacks = static_cast<Index>(s[2]);
  t.retries = static_cast<Index>(s[3]);
  t.max_condition = comm_.max(max_condition_);
  t.max_size = static_cast<int>(comm_.max(static_cast<std::int64_t>(max_support_)));
  t.max_iterations = static_cast<int>(comm_.max(static_cast<std::int64_t>(max_iterations_)));
}

void OtmSolver::seed_extents(Index p0, Index p1) {
  auto* S = points_.view(otm::kExtent);
  const auto* body = points_.ints(kBodyIndex);
  const auto* id = points_.ints(kId);
  for (Index p = p0; p < p1; ++p) {
    const double s0 = spacing_[static_cast<size_t>(body[p])];
    S[p] = Mat3::diag(s0, s0, s0);
    next_id_ = std::max(next_id_, id[p] + 1);
  }
}

void OtmSolver::project_node_velocities(Index p0, Index p1, Index a0) {
  // The mass-weighted projection of the points' velocities (exact for a body in uniform motion: the
  // shape functions are a partition of unity); the momentum counts as initial (momentum_change).
  const auto* v = points_.view(kVelocity);
  const auto* mass = points_.real(kMass);
  struct In {
    double N, m;
    Vec3 v;
  };
  struct Acc {
    double m;
    Vec3 mom;
  };
  std::vector<Acc> sums;
  otm::fold_nodes<Acc, In>(
      node_fold_scope(), sums, [&](Index a) { return a >= a0; },
      [&](Index i, In& in) {
        const Index p = inf_.owner[i];
        if (p < p0 || p >= p1) return false;
        in = In{sup_.N[inf_.entry[i]], mass[p], v[p]};
        return true;
      },
      [](Acc& acc, const In& in) {
        otm::add_product(acc.m, in.N, in.m);
        otm::add_product(acc.mom, in.N * in.m, in.v);
      });
  for (Index a = a0; a < nodes_.size(); ++a) {
    const Acc& s = sums[static_cast<size_t>(a)];
    nodes_.mass[a] = s.m;
    nodes_.v[a] = s.m > kTinyMass ? (1.0 / s.m) * s.mom : Vec3{};
    momentum0_ += s.m * nodes_.v[a];
  }
}

otm::NodeCloud OtmSolver::initial_nodes(const Scenario& sc, const OtmParams& P) {
  const Index n = points_.size();
  const auto* x = points_.view(kPosition);
  const auto* group = points_.ints(kNodeGroup);
  std::vector<int> at_elements;  // the bodies seeded at their mesh's elements
  for (std::size_t b = 0; b < sc.bodies.size(); ++b)
    if (sc.bodies[b].seeding == "elements") at_elements.push_back(static_cast<int>(b));
  if (at_elements.empty()) return otm::seed_nodes(x, group, n, sc.grid.lower, sc.grid.cell_size, dim_);
  // Bodies seeded at a mesh's elements take its vertices as their nodes (seed 003 §2): every point,
  // at its tetrahedron's centroid, lies inside the hull of that tetrahedron's four nodes.
  if (P.adaptivity)
    section_error(sc, "adaptivity", "adaptivity re-generates the nodes on the lattice of grid.cell_size; it is not "
                                    "supported with a body seeded at its mesh's elements yet");
  if (pts_.pending() > 0)
    for (const int b : at_elements)
      if (sc.bodies[static_cast<std::size_t>(b)].activation_time > 0.0 ||
          sc.bodies[static_cast<std::size_t>(b)].activation_stage != 0)
        section_error(sc, "", "a body seeded at its mesh's elements cannot arrive later yet (its nodes are the mesh's "
                              "vertices, seeded at the start)");
  if (P.shared_nodes)
    section_error(sc, "nodes", "a body seeded at its mesh's elements has the mesh's vertices as its own nodes; "
                               "otm.nodes: shared is not supported with it");
  for (int b : at_elements) {
    // The LME locality is gamma = beta h^2 with h = grid.cell_size: a mesh of another spacing s
    // would act with gamma (s/h)^2. s: the edge of the cube its tetrahedra fill six at a time.
    const BodySpec& body = sc.bodies[static_cast<std::size_t>(b)];
    const double s = mesh_spacing(body), h = sc.grid.cell_size;
    if (!(s <= 1.5 * h && s >= h / 1.5))
      throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path + ".seeding",
                      fmt::format("body '{}': its mesh's spacing {:.4g} m (the median of (6 V)^(1/3) over its "
                                  "tetrahedra) is not within a factor 1.5 of grid.cell_size {:.4g} m, the nodal "
                                  "spacing the LME shape functions assume (otm.gamma = beta h^2): set grid.cell_size "
                                  "to the mesh's spacing",
                                  body.name, s, h));
  }
  // The lattice-seeded bodies' nodes as without the meshes, then each mesh body's vertices.
  std::vector<Index> on_lattice;
  for (Index p = 0; p < n; ++p)
    if (sc.bodies[static_cast<std::size_t>(group[p])].seeding != "elements") on_lattice.push_back(p);
  std::vector<Vec3> xl(on_lattice.size());
  std::vector<std::int64_t> gl(on_lattice.size());
  for (std::size_t i = 0; i < on_lattice.size(); ++i) {
    xl[i] = x[on_lattice[i]];
    gl[i] = group[on_lattice[i]];
  }
  otm::NodeCloud nodes =
      otm::seed_nodes(xl.data(), gl.data(), static_cast<Index>(xl.size()), sc.grid.lower, sc.grid.cell_size, dim_);
  for (int b : at_elements)
    for (const Vec3& v : element_vertices(sc.bodies[static_cast<std::size_t>(b)])) {
      nodes.x.push_back(v);
      nodes.body.push_back(b);
    }
  nodes.v.assign(nodes.x.size(), Vec3{});
  nodes.f.assign(nodes.x.size(), Vec3{});
  nodes.mass.assign(nodes.x.size(), 0.0);
  return nodes;
}

const FieldStore* OtmSolver::output_nodes() {
  if (!node_out_.has(kPosition)) {
    node_out_.declare(kPosition, "m");
    node_out_.declare(kVelocity, "m/s");
    node_out_.declare(kMass, "kg");
    node_out_.declare(kNodeBody, "1");
  }
  const Index nn = nodes_.size();
  node_out_.resize(nn);
  auto* x = node_out_.view(kPosition);
  auto* v = node_out_.view(kVelocity);
  auto* m = node_out_.real(kMass);
  auto* b = node_out_.real(kNodeBody);
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

void OtmSolver::activate_pending() {
  const Index n0 = points_.size();
  if (!comm_.any(pts_.activate(time_))) return;  // every rank takes part: each makes every node
  // The arrived points (appended at the end) take their body's node set, a cell of their seeded
  // spacing (adaptivity), and nodes of their own at the vertices of the lattice cells holding them,
  // as the bodies present from the start (otm_nodes.hpp).
  const Index n = points_.size(), nn0 = nodes_.size();
  auto* group = points_.ints(kNodeGroup);
  const auto* body = points_.ints(kBodyIndex);
  for (Index p = n0; p < n; ++p) group[p] = body[p];
  if (adapt_.enabled) {
    seed_extents(n0, n);
    next_id_ = comm_.max(next_id_);  // the split ids continue after every rank's arrived points
    Fr_.resize(static_cast<size_t>(n), Mat3::identity());
  }
  std::vector<Vec3> xa(points_.view(kPosition) + n0, points_.view(kPosition) + n);
  std::vector<std::int64_t> ga(group + n0, group + n);
  gather_points(comm_, xa, ga);
  const otm::NodeCloud add = otm::seed_nodes(xa.data(), ga.data(), static_cast<Index>(xa.size()), scenario_.grid.lower,
                                             scenario_.grid.cell_size, dim_);
  auto append = [](auto& to, const auto& from) { to.insert(to.end(), from.begin(), from.end()); };
  append(nodes_.x, add.x);
  append(nodes_.v, add.v);
  append(nodes_.f, add.f);
  append(nodes_.mass, add.mass);
  append(nodes_.body, add.body);
  refresh_supports();
  project_node_velocities(n0, n, nn0);  // the fired rod's uniform velocity, exactly
}

void OtmSolver::refresh_supports() {
  if (!build_current_supports()) report_failed_solve();
}

bool OtmSolver::build_current_supports() {
  const ScopedPhase timer(seconds_.supports);
  const Index n = points_.size();
  lambda_.resize(static_cast<size_t>(n));
  // Radius scale of each point: the largest principal stretch (in the plane in 2D) of what has
  // moved its nodes apart: F, or with adaptivity the deformation since the nodes were re-generated.
  scale_.resize(static_cast<size_t>(n));
  const Mat3* F = adapt_.enabled ? Fr_.data() : points_.view(kDeformationGradient);
  for_each(0, n, [&](Index p) {
    double lo, hi;
    otm::symmetric_extremes(transpose_times(F[p], F[p]), dim_, lo, hi);
    scale_[p] = std::sqrt(std::max(hi, 1.0));
  });
  std::swap(prev_sup_, sup_);
  otm::build_supports(points_.view(kPosition), points_.ints(kNodeGroup), n, nodes_.x.data(), nodes_.body.data(),
                      nodes_.size(), sopt_, scale_.data(), prev_sup_.offset.empty() ? nullptr : &prev_sup_,
                      lambda_.data(), sup_, &candidates_);
  rebuild_influences();
  retries_ += sup_.retries;
  mean_support_ = sup_.mean_size;
  max_support_ = std::max(max_support_, sup_.max_size);
  max_iterations_ = std::max(max_iterations_, sup_.max_iterations);
  max_condition_ = std::max(max_condition_, sup_.max_condition);
  fallbacks_ += sup_.fallbacks;
  return sup_.failed < 0;
}

void OtmSolver::report_failed_solve() {
  // The point, its support nodes and the state of the solve (never a NaN weight handed on).
  const Index p = sup_.failed;
  const Index k0 = sup_.offset[p], k1 = sup_.offset[p + 1];
  // On the undeformed lattice nothing has moved: the support parameters cannot work at all.
  if (steps_ == 0)
    section_error(scenario_, "gamma",
                  fmt::format("on the undeformed lattice point {} has {} support nodes within the support radius "
                              "h sqrt(-ln(support_tolerance) / gamma) = {:.4g} m = {:.3g} h (otm.gamma = {:g}, "
                              "otm.support_tolerance = {:g}), and its shape functions need at least {}: lower gamma "
                              "(the Taylor bar examples use 1.8) or raise support_tolerance",
                              p, k1 - k0, otm::support_radius(sopt_), otm::support_radius(sopt_) / sopt_.h,
                              sopt_.gamma, sopt_.tolerance, sopt_.min_support > 0 ? sopt_.min_support : dim_ + 2));
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
                        "after {} iterations{}, condition number of the Hessian {:.3g}; support nodes: {}. {}",
                        k1 - k0, otm::support_radius(sopt_) * std::clamp(scale_[p], 1.0, otm::kMaxScale),
                        sopt_.min_support > 0 ? sopt_.min_support : dim_ + 2, sopt_.gamma, r.residual, r.iterations,
                        r.used_fallback ? " (with the fallback)" : "", r.condition, nodes,
                        adapt_.enabled
                            ? "It failed on freshly re-generated lattice nodes too"
                            : "The point has probably left the convex hull of its nodes (otm.adaptivity: on)"),
            steps_, time_);
}

void OtmSolver::adapt() {
  // Its support builds count as `supports`, the rest (splits, metrics, re-generation) as `adapt`.
  const auto t0 = std::chrono::steady_clock::now();
  const double supports0 = seconds_.supports;
  bool regenerate = false;
  std::vector<std::string> extensive = {kMass.name(), kReferenceVolume.name(), kInternalEnergy.name(),
                                        kPlasticWork.name()};
  for (const std::string& a : pts_.load_area_fields()) extensive.push_back(a);
  // Only held faces (walls, symmetry planes, fixed faces) keep a split parallel to them: a free
  // face is no obstacle, and material may flow past the box there (the 750 m/s bar's disc).
  Vec3 held_lower = scenario_.grid.lower, held_upper = scenario_.grid.upper;
  for (int ax = 0; ax < 3; ++ax) {
    if (scenario_.grid.faces[2 * ax] == FaceBC::Free) held_lower[ax] = -kInf;
    if (scenario_.grid.faces[2 * ax + 1] == FaceBC::Free) held_upper[ax] = kInf;
  }
  // Several ranks: a parent's neighbours may be another rank's points (the children's state).
  const std::optional<otm::Neighbourhood> around = comm_.distributed() ? neighbourhood_for_splits() : std::nullopt;
  const Index n_before = points_.size();
  std::int64_t next_id = next_id_;
  const std::vector<Index> parents =
      otm::split_points(points_, extensive, spacing_, dim_, axisym_, held_lower, held_upper, adapt_,
                        split_state_, kFailedField, next_id, around ? &*around : nullptr);
  const Index split_count = comm_.distributed() ? number_children(parents, n_before) : static_cast<Index>(parents.size());
  if (!comm_.distributed()) next_id_ = next_id;
  if (!parents.empty()) {
    // The second children take their parents' solver state; a child outside the hull of its
    // nodes fails its LME solve below, which re-generates the nodes.
    pts_.mark_reordered();
    for (const Index p : parents) {
      Fr_.push_back(Fr_[p]);
      lambda_.push_back(lambda_[p]);
    }
  }
  splits_ += split_count;
  {
    regenerate = !build_current_supports();
    // The seed's distance metric (Fig. 5-2), seen from the points: a point whose nearest node is
    // farther than node_gap h has lost the nodes that resolve the motion around it.
    const auto* x = points_.view(kPosition);
    const double gap2 = std::pow(adapt_.node_gap * sopt_.h, 2);
    for (Index p = 0; p < points_.size() && !regenerate; ++p) {
      double near2 = kInf;
      for (Index k = sup_.offset[p]; k < sup_.offset[p + 1]; ++k) {
        Vec3 d = x[p] - nodes_.x[sup_.node[k]];
        if (dim_ == 2) d[2] = 0.0;
        near2 = std::min(near2, dot(d, d));
      }
      regenerate = near2 > gap2;
    }
    // Conditioning (seed 003 ch. 5.2): an LME Hessian this ill-conditioned means a point's nodes
    // have collapsed onto a line or plane around it.
    if (!regenerate) regenerate = sup_.max_condition > adapt_.max_condition;
    regenerate = comm_.any(regenerate);  // the nodes are every rank's: all re-generate or none
    if (!regenerate) regenerate = otm::nodes_crowded(nodes_, adapt_.node_crowding * sopt_.h, dim_);
  }
  // A split conserves the points' mass, momentum sum_p m_p v_p and energies exactly; the nodes'
  // lumped masses then follow at the next assembly, as they do every step in the momentum form
  // (docs/validation.md: the residual this leaves).
  if (regenerate) regenerate_nodes();
  seconds_.adapt += seconds_since(t0) - (seconds_.supports - supports0);
}

void OtmSolver::regenerate_nodes() {
  const Index n = points_.size();
  const otm::NodeCloud old = std::move(nodes_);
  double ke0 = 0.0;
  for (Index b = 0; b < old.size(); ++b) ke0 += 0.5 * old.mass[b] * dot(old.v[b], old.v[b]);
  {
    // Several ranks: the nodes over every rank's points.
    std::vector<Vec3> xa(points_.view(kPosition), points_.view(kPosition) + n);
    std::vector<std::int64_t> ga(points_.ints(kNodeGroup), points_.ints(kNodeGroup) + n);
    gather_points(comm_, xa, ga);
    nodes_ = otm::seed_nodes(xa.data(), ga.data(), static_cast<Index>(xa.size()), scenario_.grid.lower,
                             scenario_.grid.cell_size, dim_);
  }
  const Index nn = nodes_.size();
  // Velocities of the new nodes: the old nodes' LME interpolant evaluated at them,
  // v_a = sum_b N_b(x_a) v_b. An interpolation, not the mass-weighted projection from the points
  // (Li, Habbal & Ortiz 2010 eq. 20), which averages the field over a support and removes kinetic
  // energy at every re-generation (the 750 m/s bar at 1.6 mm lost 64 % of its energy to it, 14 %
  // with the interpolation; docs/validation.md).
  {
    std::vector<double> wide(static_cast<size_t>(nn), otm::kMaxScale);
    std::vector<Vec3> lam(static_cast<size_t>(nn));
    otm::Supports at;
    otm::build_supports(nodes_.x.data(), nodes_.body.data(), nn, old.x.data(), old.body.data(), old.size(), sopt_,
                        wide.data(), nullptr, lam.data(), at);
    std::vector<char> inside(static_cast<size_t>(nn), 1);
    for (const Index a : at.unsolved) inside[a] = 0;
    for_each(0, nn, [&](Index a) {
      Vec3 v;
      if (inside[a])
        for (Index k = at.offset[a]; k < at.offset[a + 1]; ++k) v += at.N[k] * old.v[at.node[k]];
      nodes_.v[a] = v;
    });
    interpolated_.swap(inside);
  }
  lambda_.assign(static_cast<size_t>(n), Vec3{});
  Fr_.assign(static_cast<size_t>(n), Mat3::identity());
  sup_ = otm::Supports{};  // no previous supports: their node indices are gone
  prev_sup_ = otm::Supports{};
  // Several ranks: a failed solve stops the run after the sums below, which every rank takes part in.
  const bool solved = build_current_supports();
  if (!solved && !comm_.distributed()) report_failed_solve();
  // Lumped masses on the new nodes (eq. 2.13).
  const auto* v = points_.view(kVelocity);
  const auto* mass = points_.real(kMass);
  const auto* pbody = points_.ints(kNodeGroup);
  const size_t nb = scenario_.bodies.size();  // groups are numbered below the body count
  // sum_p m_p v_p per body (the old nodes' momentum, exactly), over every rank's points in id order.
  std::vector<Vec3> p_points(nb);
  {
    std::vector<double> ms(mass, mass + n);
    std::vector<Vec3> vs(v, v + n);
    std::vector<std::int64_t> gs(pbody, pbody + n);
    std::vector<Vec3> xs;
    if (comm_.distributed()) points_in_id_order(xs, vs, gs, &ms);
    for (size_t q = 0; q < ms.size(); ++q) p_points[static_cast<size_t>(gs[q])] += ms[q] * vs[q];
  }
  nodes_.mass = lumped_masses();
  // A node outside the old nodes' hull (a lattice vertex beyond the old edge of the material)
  // takes the velocity of its nearest point, v_p = sum N_b v_b: an extrapolation, not an average.
  {
    const Vec3* xp = points_.view(kPosition);
    const Vec3* vp = v;
    const std::int64_t* gp = pbody;
    Index np = n;
    // Several ranks: every rank's points, in id order (the serial run's point order; ties go to
    // the first).
    std::vector<Vec3> xs, vs;
    std::vector<std::int64_t> gs;
    if (comm_.distributed()) {
      points_in_id_order(xs, vs, gs);
      xp = xs.data();
      vp = vs.data();
      gp = gs.data();
      np = static_cast<Index>(xs.size());
    }
    const CellBins bins(xp, np, std::sqrt(static_cast<double>(dim_)) * scenario_.grid.cell_size, dim_);
    for (Index a = 0; a < nn; ++a) {
      if (interpolated_[a]) continue;
      double best = kInf;
      Index q = -1;
      bins.visit(nodes_.x[a], [&](Index p) {
        if (gp[p] != nodes_.body[a]) return;
        Vec3 d = xp[p] - nodes_.x[a];
        if (dim_ == 2) d[2] = 0.0;
        const double d2 = dot(d, d);
        if (d2 < best || (d2 == best && p < q)) {
          best = d2;
          q = p;
        }
      });
      nodes_.v[a] = q >= 0 ? vp[q] : Vec3{};
    }
  }
  // Linear momentum is restored exactly by a uniform velocity change of each body's nodes that are
  // free to move along the component (not on a fixed face, nor normal to a symmetry face or a wall,
  // whose condition would undo the change at the next step; the radial component of an
  // axisymmetric run is not a conserved quantity). The interpolation error it corrects is of the
  // order of the field's curvature times h^2.
  const GridSpec& g = scenario_.grid;
  const double tol = 1e-9 * g.cell_size;
  auto held = [&](Index a, int c) {
    if (axisym_ && c == 0) return true;
    for (int ax = 0; ax < dim_; ++ax)
      for (int side = 0; side < 2; ++side) {
        const FaceBC bc = g.faces[2 * ax + side];
        if (bc != FaceBC::Fixed && !((bc == FaceBC::Symmetry || bc == FaceBC::Wall) && ax == c)) continue;
        if (std::abs(nodes_.x[a][ax] - (side == 0 ? g.lower[ax] : g.upper[ax])) <= tol) return true;
      }
    return false;
  };
  for (int c = 0; c < dim_; ++c) {
    std::vector<double> dp(nb, 0.0), mfree(nb, 0.0);
    for (size_t b = 0; b < nb; ++b) dp[b] = p_points[b][c];
    for (Index a = 0; a < nn; ++a) {
      const size_t b = static_cast<size_t>(nodes_.body[a]);
      dp[b] -= nodes_.mass[a] * nodes_.v[a][c];
      if (!held(a, c)) mfree[b] += nodes_.mass[a];
    }
    for (Index a = 0; a < nn; ++a) {
      const size_t b = static_cast<size_t>(nodes_.body[a]);
      if (!held(a, c) && mfree[b] > kTinyMass) nodes_.v[a][c] += dp[b] / mfree[b];
    }
  }
  double ke1 = 0.0;
  for (Index a = 0; a < nn; ++a) ke1 += 0.5 * nodes_.mass[a] * dot(nodes_.v[a], nodes_.v[a]);
  remap_work_ += ke1 - ke0;
  ++regenerations_;
  if (!solved) report_failed_solve();
}

std::optional<otm::Neighbourhood> OtmSolver::neighbourhood_for_splits() {
  // Only when some rank has a point stretched enough to split (split_points' test before its face
  // rules) and the children interpolate their state: then every rank sends every other its points.
  if (!split_state_.interpolate) return std::nullopt;
  const Index n = points_.size();
  const auto* S = points_.view(otm::kExtent);
  const auto* body = points_.ints(kBodyIndex);
  bool candidate = false;
  for (Index p = 0; p < n && !candidate; ++p) {
    double lo, hi;
    otm::symmetric_extremes(S[p] * transpose(S[p]), dim_, lo, hi);
    candidate = std::sqrt(std::max(hi, 0.0)) > adapt_.split_stretch * spacing_[static_cast<size_t>(body[p])];
  }
  if (!comm_.any(candidate)) return std::nullopt;
  std::vector<Index> all(static_cast<size_t>(n));
  for (Index p = 0; p < n; ++p) all[p] = p;
  const std::vector<std::vector<char>> received =
      comm_.all_to_all(std::vector<std::vector<char>>(static_cast<size_t>(comm_.size()), points_.pack(all)));
  FieldStore gathered = points_;
  for (int r = 0; r < comm_.size(); ++r)
    if (r != comm_.rank()) gathered.append_packed(received[r].data(), received[r].size());
  // In id order, the serial run's point order: a parent visits its neighbours in the order the
  // serial run does, and its children's state is the serial run's to the bit.
  const auto* id = gathered.ints(kId);
  std::vector<Index> order(static_cast<size_t>(gathered.size()));
  for (Index q = 0; q < gathered.size(); ++q) order[q] = q;
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return id[a] < id[b]; });
  otm::Neighbourhood around{gathered.empty_like(), std::vector<Index>(static_cast<size_t>(n))};
  around.points.append_from(gathered, order);
  for (Index k = 0; k < gathered.size(); ++k)
    if (order[k] < n) around.own_at[static_cast<size_t>(order[k])] = k;
  return around;
}

Index OtmSolver::number_children(const std::vector<Index>& parents, Index first_child) {
  // A serial run numbers the second children in its point order, which is id order while the
  // bodies arriving later come after the others in the deck (points are appended with ids above
  // every other). Here the same: by the parents' ids over every rank.
  auto* id = points_.ints(kId);
  std::vector<std::int64_t> mine;
  for (const Index p : parents) mine.push_back(id[p]);
  std::vector<int> counts;
  std::vector<std::int64_t> every = comm_.all_gather(mine, counts);
  std::sort(every.begin(), every.end());
  for (size_t i = 0; i < parents.size(); ++i) {
    const auto at = std::lower_bound(every.begin(), every.end(), mine[i]) - every.begin();
    id[first_child + static_cast<Index>(i)] = next_id_ + at;
  }
  next_id_ += static_cast<std::int64_t>(every.size());
  return static_cast<Index>(every.size());
}

void OtmSolver::points_in_id_order(std::vector<Vec3>& x, std::vector<Vec3>& v, std::vector<std::int64_t>& group,
                                   std::vector<double>* mass) const {
  const Index n = points_.size();
  const auto* xp = points_.view(kPosition);
  const auto* vp = points_.view(kVelocity);
  const auto* mp = points_.real(kMass);
  std::vector<double> rows;
  for (Index p = 0; p < n; ++p) rows.insert(rows.end(), {xp[p][0], xp[p][1], xp[p][2], vp[p][0], vp[p][1], vp[p][2], mp[p]});
  IdOrdered all = gather_in_id_order(comm_, rows, 7, points_.ints(kId), points_.ints(kNodeGroup), n);
  const std::size_t m = all.id.size();
  x.resize(m);
  v.resize(m);
  if (mass) mass->resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const double* r = all.rows.data() + 7 * k;
    x[k] = Vec3{{r[0], r[1], r[2]}};
    v[k] = Vec3{{r[3], r[4], r[5]}};
    if (mass) (*mass)[k] = r[6];
  }
  group = std::move(all.group);
}

void OtmSolver::assemble() {
  // Node-wise folds over the influence domains: the same bits for any thread or rank count.
  const ScopedPhase timer(seconds_.assemble);
  const Index nn = nodes_.size();
  const auto* mass = points_.real(kMass);
  const auto* vol = points_.real(kVolume);
  const auto* stress = points_.view(kStress);
  const auto* x = points_.view(kPosition);
  const std::vector<Vec3>& fext = loads_.total();
  const bool has_ext = !fext.empty();
  const bool axisym = axisym_;
  struct In {
    double N;
    Vec3 g;
    double m, V;
    Mat3 s;
    double r;  // x_p[0]: the radius (axisymmetric)
    Vec3 fext;
  };
  struct Acc {
    double m;
    Vec3 f;
  };
  std::vector<Acc> sums;
  otm::fold_nodes<Acc, In>(
      node_fold_scope(), sums, [](Index) { return true; },
      [&](Index i, In& in) {
        const Index k = inf_.entry[i], p = inf_.owner[i];
        in.N = sup_.N[k];
        in.g = sup_.dN[k];
        in.m = mass[p];
        in.V = vol[p];
        in.s = stress[p];
        in.r = x[p][0];
        in.fext = has_ext ? fext[p] : Vec3{};
        return true;
      },
      [axisym, has_ext](Acc& acc, const In& in) {
        otm::add_product(acc.m, in.N, in.m);
        // f_a = -V_p sigma_p grad N_a + N_a f_ext,p (seed 003 Algorithm 1 line 9, the weak form 2.7).
        const Mat3& s = in.s;
        const Vec3& g = in.g;
        for (int r = 0; r < 3; ++r)
          otm::add_product(acc.f[r], -in.V, std::fma(s(r, 2), g[2], std::fma(s(r, 1), g[1], s(r, 0) * g[0])));
        if (axisym) acc.f[0] -= in.V * s(2, 2) * in.N / in.r;  // hoop term (per-radian volume)
        if (has_ext) otm::add_product(acc.f, in.N, in.fext);
      });
  for_each(0, nn, [&](Index a) {
    nodes_.mass[a] = sums[static_cast<size_t>(a)].m;
    nodes_.f[a] = sums[static_cast<size_t>(a)].f;
  });
}

std::vector<std::pair<Index, Vec3>> OtmSolver::light_nodes() const {
  // A node outside the body, reached only by the tails of its points' shape functions, has a lumped
  // mass (seed 003 eq. 2.13) and a force (line 9) that both scale with those tails, N_a ~
  // exp(-beta |x_p - x_a|^2): its acceleration f_a / m_a ~ 2 beta |x_p - x_a| |sigma_p| / rho_p
  // does not vanish with them, while its pull back towards the material (the stress its own motion
  // makes, ~ N_a^2) does. Integrated like the others, such a node drifts away at km/s and carries
  // that speed into the body when the material reaches it again (the lattice Taylor bar at 0.4 mm:
  // a node of 1e-21 kg at 9.8 km/s, docs/validation.md). It takes the velocity the points give it
  // instead, the mass-weighted projection with which Li, Habbal & Ortiz, IJNME 83 (2010) 1541,
  // define every node's momentum, l_a = sum_p N_a(x_p) m_p v_p (the seed's eq. 2.14 replaces it by
  // M v for the others).
  const Index n = points_.size(), nn = nodes_.size();
  const auto* mass = points_.real(kMass);
  double lightest = kInf;
  for (Index p = 0; p < n; ++p) lightest = std::min(lightest, mass[p]);
  const double bar = kLightNodeShare * -comm_.max(-lightest);
  std::vector<std::pair<Index, Vec3>> light;
  for (Index a = 0; a < nn; ++a)
    if (nodes_.mass[a] > kTinyMass && nodes_.mass[a] < bar) light.emplace_back(a, Vec3{});
  if (light.empty()) return light;  // the same on every rank: the masses are the ranks' totals
  const auto* v = points_.view(kVelocity);
  std::vector<char> is_light(static_cast<size_t>(nn), 0);
  for (const auto& l : light) is_light[static_cast<size_t>(l.first)] = 1;
  struct In {
    double N, m;
    Vec3 v;
  };
  struct Acc {
    Vec3 l;
  };
  std::vector<Acc> momentum;
  otm::fold_nodes<Acc, In>(
      node_fold_scope(), momentum, [&](Index a) { return is_light[static_cast<size_t>(a)] != 0; },
      [&](Index i, In& in) {
        const Index p = inf_.owner[i];
        in = In{sup_.N[inf_.entry[i]], mass[p], v[p]};
        return true;
      },
      [](Acc& acc, const In& in) { otm::add_product(acc.l, in.N * in.m, in.v); });
  for (auto& [a, va] : light) va = (1.0 / nodes_.mass[a]) * momentum[static_cast<size_t>(a)].l;
  return light;
}

std::vector<Vec3> OtmSolver::contact_node_forces() {
  // Each point's stiffness bound m_p w_p^2, w_p^2 the largest omega_a^2 of its nodes (stable_dt
  // computed them for these supports), the pinball forces at the points, then gathered node by
  // node over the influence domains as the external forces are (f_a += N_a f_p).
  const Index n = points_.size(), nn = nodes_.size();
  const auto* mass = points_.real(kMass);
  std::vector<double> stiff(static_cast<size_t>(n), 0.0);
  for_each(0, n, [&](Index p) {
    double w2 = 0.0;
    for (Index k = sup_.offset[p]; k < sup_.offset[p + 1]; ++k)
      if (const Index a = sup_.node[k]; a < static_cast<Index>(omega2_.size())) w2 = std::max(w2, omega2_[a]);
    stiff[p] = mass[p] * w2;
  });
  std::vector<Vec3> fp;
  if (!comm_.distributed()) {
    contact_pairs_ = otm::pinball_forces(points_.view(kPosition), points_.real(kVolume), points_.ints(kNodeGroup),
                                         stiff.data(), n, contact_penalty_, {dim_, axisym_}, fp);
  } else {
    // Several ranks: every rank's balls, gathered in id order (the serial run's point order, which
    // each point's sum over its partners follows); this rank keeps its points' forces.
    const auto* xp = points_.view(kPosition);
    const auto* vol = points_.real(kVolume);
    const auto* id = points_.ints(kId);
    std::vector<double> rows;
    for (Index p = 0; p < n; ++p) rows.insert(rows.end(), {xp[p][0], xp[p][1], xp[p][2], vol[p], stiff[p]});
    const IdOrdered all_points = gather_in_id_order(comm_, rows, 5, id, points_.ints(kNodeGroup), n);
    const std::vector<std::int64_t>& ids = all_points.id;
    const Index all = static_cast<Index>(ids.size());
    std::vector<Vec3> x(static_cast<size_t>(all));
    std::vector<double> va(static_cast<size_t>(all)), sa(static_cast<size_t>(all));
    for (Index k = 0; k < all; ++k) {
      const double* r = all_points.rows.data() + 5 * k;
      x[k] = Vec3{{r[0], r[1], r[2]}};
      va[k] = r[3];
      sa[k] = r[4];
    }
    std::vector<Vec3> fall;
    contact_pairs_ = otm::pinball_forces(x.data(), va.data(), all_points.group.data(), sa.data(), all, contact_penalty_,
                                         {dim_, axisym_}, fall);
    fp.resize(static_cast<size_t>(n));
    for (Index p = 0; p < n; ++p)
      fp[p] = fall[static_cast<size_t>(std::lower_bound(ids.begin(), ids.end(), id[p]) - ids.begin())];
  }
  std::vector<Vec3> f(static_cast<size_t>(nn), Vec3{});
  if (contact_pairs_ == 0) return f;
  struct In {
    double N;
    Vec3 f;
  };
  struct Acc {
    Vec3 f;
  };
  std::vector<Acc> sums;
  otm::fold_nodes<Acc, In>(
      node_fold_scope(), sums, [](Index) { return true; },
      [&](Index i, In& in) {
        in = In{sup_.N[inf_.entry[i]], fp[inf_.owner[i]]};
        return true;
      },
      [](Acc& acc, const In& in) { otm::add_product(acc.f, in.N, in.f); });
  for (Index a = 0; a < nn; ++a) f[a] = sums[static_cast<size_t>(a)].f;
  return f;
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
  // A body whose time has come joins before the step's limit is set, so its stiffness counts.
  if (pending_anywhere()) activate_pending();
  const ScopedPhase timer(seconds_.stable_dt);
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
  const bool none = comm_.distributed() ? comm_.sum(static_cast<std::int64_t>(n)) == 0 : n == 0;
  if (!(c > 0.0) || none) return std::min(max_dt, scenario_.simulation.end_time);
  if (symmetric_bound_) symmetric_node_bounds(c);
  else row_sum_node_bounds(c);
  double w2 = 0.0;
  for (Index a = 0; a < nn; ++a) w2 = std::max(w2, omega2_[a]);
  w2 = comm_.max(w2);
  // A penalty wall's spring k_a = penalty m_a omega_a^2 raises a wall node's omega^2 by the
  // factor 1 + penalty.
  // Pinball contact's springs (otm_contact.hpp) raise it by about 1 + contact_penalty.
  const double bound = 2.0 / std::sqrt(1.0 + (penalty_ ? penalty_factor_ : 0.0) + (contact_ ? contact_penalty_ : 0.0));
  const double dt = w2 > 0.0 ? scenario_.simulation.cfl * bound / std::sqrt(w2) : scenario_.simulation.end_time;
  return std::min(dt, max_dt);
}

void OtmSolver::row_sum_node_bounds(double c) {
  const Index n = points_.size(), nn = nodes_.size();
  const auto* mass = points_.real(kMass);
  const auto* x = points_.view(kPosition);
  auto g = [&](Index p, Index kk) {
    double v = norm(sup_.dN[kk]);
    if (axisym_) v += sup_.N[kk] / x[p][0];
    return v;
  };
  // G_p = sum_b g_b,p per point, then omega_a^2 node by node over the influence domains (a
  // gather: parallel and deterministic).
  std::vector<double> G(static_cast<size_t>(n), 0.0);
  for_each_heavy(0, n, [&](Index p) {
    double s = 0.0;
    for (Index kk = sup_.offset[p]; kk < sup_.offset[p + 1]; ++kk) s += g(p, kk);
    G[p] = s;
  });
  // The node's sums: m_a and sum_p m_p G_p g_a,p.
  struct In {
    double m, G, g, N;
  };
  struct Acc {
    double k, m;
  };
  std::vector<Acc> sums;
  otm::fold_nodes<Acc, In>(
      node_fold_scope(), sums, [](Index) { return true; },
      [&](Index i, In& in) {
        const Index kk = inf_.entry[i], p = inf_.owner[i];
        in = In{mass[p], G[p], g(p, kk), sup_.N[kk]};
        return true;
      },
      [](Acc& acc, const In& in) {
        otm::add_product(acc.k, in.m * in.G, in.g);
        otm::add_product(acc.m, in.N, in.m);
      });
  omega2_.assign(static_cast<size_t>(nn), 0.0);
  for_each(0, nn, [&](Index a) {
    const Acc& s = sums[static_cast<size_t>(a)];
    if (s.m > kTinyMass) omega2_[a] = s.k / s.m * c * c;
  });
}

void OtmSolver::symmetric_node_bounds(double c) {
  // M^-1 K and A = M^-1/2 K M^-1/2 have the same eigenvalues, and Gershgorin's theorem bounds them
  // by A's largest row sum: omega_max^2 <= max_a sum_b |K_ab| / sqrt(m_a m_b). With the tangent
  // bound of stable_dt, |K_ab| <= sum_p m_p c^2 g_a,p g_b,p, so
  //   omega_a^2 <= c^2 / sqrt(m_a) sum_p m_p g_a,p H_p,   H_p = sum_b g_b,p / sqrt(m_b).
  // On a lattice of equal masses this is the row sum of M^-1 K; a node that carries a small share
  // of its points' mass (a far node of a support, N_a ~ 0, whose g_a,p / N_a ~ 2 beta |x_p - x_a|
  // stays large) no longer sets it: its couplings to heavy nodes are scaled by sqrt(m_a m_b), not
  // by m_a alone (the lumped-mass bound of Belytschko, Liu & Moran (2000) §6.3 with the symmetric
  // scaling of the mass matrix).
  const Index n = points_.size(), nn = nodes_.size();
  const auto* mass = points_.real(kMass);
  const auto* x = points_.view(kPosition);
  // A failed point of a material whose failed points carry no stress (erosion zero_stress) has no
  // stiffness, so its terms could all go; its hoop term N_a / r_p does, since an eroded point that
  // drifts onto the axis (r_p -> 0) would otherwise set the step alone (the rod through a plate at
  // 0.125 mm: r_p = h/480, the step 1/43 of the first; docs/validation.md).
  std::vector<char> hoop(static_cast<size_t>(n), axisym_ ? 1 : 0);
  if (axisym_ && points_.has(kFailed)) {
    const auto* failed = points_.real(kFailed);
    const auto* mat = points_.ints(kMaterialIndex);
    for (Index p = 0; p < n; ++p)
      if (failed[p] > 0.0 && pts_.materials()[static_cast<size_t>(mat[p])]->failed_points_are_stress_free())
        hoop[p] = 0;
  }
  auto g = [&](Index p, Index kk) { return coupling(sup_, kk, x[p], hoop[p] != 0); };
  const std::vector<double> m = lumped_masses();
  std::vector<double> H(static_cast<size_t>(n), 0.0);
  for_each_heavy(0, n, [&](Index p) {
    double s = 0.0;
    for (Index kk = sup_.offset[p]; kk < sup_.offset[p + 1]; ++kk)
      if (const Index b = sup_.node[kk]; m[b] > kTinyMass) s += g(p, kk) / std::sqrt(m[b]);
    H[p] = s;
  });
  struct RowIn {
    double m, g, H;
  };
  struct Sum {
    double s;
  };
  std::vector<Sum> k;
  otm::fold_nodes<Sum, RowIn>(
      node_fold_scope(), k, [](Index) { return true; },
      [&](Index i, RowIn& in) {
        const Index kk = inf_.entry[i], p = inf_.owner[i];
        in = RowIn{mass[p], g(p, kk), H[p]};
        return true;
      },
      [](Sum& acc, const RowIn& in) { otm::add_product(acc.s, in.m * in.g, in.H); });
  omega2_.assign(static_cast<size_t>(nn), 0.0);
  for_each(0, nn, [&](Index a) {
    if (m[a] > kTinyMass) omega2_[a] = k[static_cast<size_t>(a)].s / std::sqrt(m[a]) * c * c;
  });
}

void OtmSolver::step(double dt) {
  if (!comm_.distributed()) {
    step_local(dt);
    if (removed_) drop_orphan_nodes();
    reduce_support_statistics();
    return;
  }
  // A failure on one rank stops every rank with the same diagnostic: nothing after the first place
  // a rank can throw (the kinematics check) waits for the other ranks.
  run_agreed(comm_, [&] { step_local(dt); });
  if (comm_.any(removed_)) drop_orphan_nodes();
  reduce_support_statistics();
}

void OtmSolver::step_local(double dt) {
  const Index n = points_.size(), nn = nodes_.size();
  loads_.compute(scenario_, points_, time_);
  assemble();
  // Rigid walls by penalty: a spring k_a = penalty m_a omega_a^2 on how far a node is behind the
  // wall, omega_a^2 the node's Gershgorin bound (stable_dt): as stiff as the material around the
  // node times `penalty`, independent of the time step (stable_dt shortens the step for it).
  double wall_force = 0.0;
  std::vector<Vec3> fpen;
  std::optional<ScopedPhase> phase(std::in_place, seconds_.nodes);
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
  std::vector<Vec3> fcon;
  if (contact_) fcon = contact_node_forces();
  // Central difference with a variable step (Algorithm 1 line 11, l_k = M_k v_k): v_a gains
  // (dt_k + dt_k+1)/2 f_a / m_a; damping -c v (stages) with its work booked (midpoint velocity).
  const double dt_mid = 0.5 * (dt_prev_ + dt);
  v_start_.assign(static_cast<size_t>(nn), Vec3{});
  const std::vector<std::pair<Index, Vec3>> light = light_nodes();
  std::vector<char> carried;
  if (!light.empty()) {
    carried.assign(static_cast<size_t>(nn), 0);
    for (const auto& l : light) carried[static_cast<size_t>(l.first)] = 1;
  }
  const double c = damping_;
  double dw[3];
  deterministic_sum<3>(0, nn, [&](Index a, double* o) {
    const double m = nodes_.mass[a];
    if (!(m > kTinyMass)) return;  // a node no point reaches: it keeps its velocity, carries nothing
    const Vec3 v0 = nodes_.v[a];
    v_start_[a] = v0;
    if (!carried.empty() && carried[static_cast<size_t>(a)]) return;  // light: set below
    Vec3 f = nodes_.f[a];
    if (penalty_) f += fpen[a];
    if (contact_) f += fcon[a];
    const Vec3 acc = (1.0 / m) * f - c * v0;
    nodes_.v[a] = v0 + dt_mid * acc;
    const Vec3 vmid = 0.5 * (v0 + nodes_.v[a]);
    o[0] -= dt_mid * c * m * dot(v0, vmid);
    if (penalty_) o[1] += dt_mid * dot(fpen[a], vmid);
    if (contact_) o[2] += dt_mid * dot(fcon[a], vmid);
  }, dw);
  // Sums over the nodes, which every rank holds whole: totals already.
  damping_work_ += dw[0];
  wall_work_ += dw[1];
  contact_work_ += dw[2];
  carried_node_steps_ += static_cast<std::int64_t>(light.size());
  for (const auto& [a, v_points] : light) {
    const Vec3 v0 = nodes_.v[a];
    remap_work_ += 0.5 * nodes_.mass[a] * (dot(v_points, v_points) - dot(v0, v0));
    nodes_.v[a] = v_points;
  }
  apply_face_conditions(dt);
  for_each(0, nn, [&](Index a) { nodes_.x[a] += dt * nodes_.v[a]; });

  // Points follow the nodes (Algorithm 1 lines 12-16) with the shape functions of x_p^k.
  phase.emplace(seconds_.points);
  auto* x = points_.view(kPosition);
  auto* v = points_.view(kVelocity);
  auto* F = points_.view(kDeformationGradient);
  auto* L = points_.view(kVelocityGradient);
  auto* vol = points_.real(kVolume);
  const auto* vol0 = points_.real(kReferenceVolume);
  const std::vector<Vec3>& fext = loads_.total();
  const bool has_ext = !fext.empty();
  Mat3* extent = adapt_.enabled ? points_.view(otm::kExtent) : nullptr;
  std::atomic<Index> bad{n};
  std::atomic<std::int64_t> discarded{0};
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
    const Mat3 dF = Mat3::identity() + dt * l;
    const Mat3 F_new = dF * F[p];
    const double J = det(F_new);
    if (!(J > 0.0 && all_finite(F_new)) && all_finite(xn) && pts_.failed_stress_free(p)) [[unlikely]] {
      // As in MPM: a point eroded under zero_stress keeps F_n (thesis eq. 6.14), so an inverting
      // increment of it, which nothing resists, is its nodes' and not its material's: discarded
      // (the point moves; its F, shape, volume and state stay) and counted, not a stop.
      L[p] = Mat3{};
      vol[p] = vol0[p] * det(F[p]);
      discarded.fetch_add(1, std::memory_order_relaxed);
      return;
    }
    F[p] = F_new;
    if (extent) {
      extent[p] = dF * extent[p];
      Fr_[p] = dF * Fr_[p];
    }
    vol[p] = vol0[p] * J;
    if (!(J > 0.0) || !all_finite(F[p]) || !all_finite(xn)) {
      Index cur = bad.load();
      while (p < cur && !bad.compare_exchange_weak(cur, p)) {
      }
    }
  }, ew);
  external_work_ += comm_.sum(ew[0]);
  // Every rank averages (its nodal sums are collective), unless a point failed on any rank.
  if (fbar_on_ && !comm_.any(bad.load() < n)) {
    const otm::NodeFoldScope scope = node_fold_scope();
    fbar_.apply(sup_, nn, dim_ == 2 && !axisym_, dt,
                {n, L, F, vol, vol0, extent, adapt_.enabled ? Fr_.data() : nullptr}, &scope);
  }
  dt_prev_ = dt;
  time_ += dt;
  ++steps_;
  if (const std::int64_t d = discarded.load()) pts_.add_frozen_increments_discarded(d);
  if (const Index p = bad.load(); p < n)
    pts_.fail(p, "inverted or non-finite deformation gradient (J <= 0 or NaN)", steps_, time_);
  removed_ = delete_exits_ && remove_exits();
  phase.emplace(seconds_.material);
  pts_.update_stress(dt, steps_, time_);
  phase.reset();
  if (adapt_.enabled) adapt();
  else refresh_supports();
}

bool OtmSolver::remove_exits() {
  // Points outside the grid box leave the run (simulation.on_particle_exit: delete); the points
  // layer books their mass, momentum and kinetic and internal energy as removed, with the points'
  // interpolated velocity (the nodes' kinetic energy they took differs by the velocity's variation
  // over their supports, which the energy residual shows).
  const Index n = points_.size();
  const auto* x = points_.view(kPosition);
  const GridSpec& g = scenario_.grid;
  std::vector<char> keep(static_cast<size_t>(n), 1);
  bool any = false;
  for (Index p = 0; p < n; ++p)
    for (int a = 0; a < dim_; ++a)
      if (!(x[p][a] >= g.lower[a] && x[p][a] <= g.upper[a])) {
        keep[p] = 0;
        any = true;
      }
  if (!any) return false;
  pts_.remove(keep);
  // The solver's own per-point arrays follow (the supports are rebuilt after the step).
  auto compact = [&](auto& v) {
    if (v.size() != static_cast<size_t>(n)) return;
    size_t k = 0;
    for (Index p = 0; p < n; ++p)
      if (keep[p]) v[k++] = v[p];
    v.resize(k);
  };
  compact(lambda_);
  compact(Fr_);
  compact(scale_);
  prev_sup_ = otm::Supports{};  // of the old numbering: no retries from it
  return true;
}

void OtmSolver::drop_orphan_nodes() {
  // Nodes that no point supports any more (their points deleted) carry nothing; kept, they would
  // drift on at their last velocity and could enter a later support. They go, and the supports'
  // node numbers follow.
  const Index nn = nodes_.size();
  std::vector<std::int32_t> renumber(static_cast<size_t>(nn), -1);
  for (const std::int32_t a : sup_.node) renumber[a] = 0;
  if (comm_.distributed()) {  // a node any rank's points use stays
    std::vector<std::int64_t> used(static_cast<size_t>(nn));
    for (Index a = 0; a < nn; ++a) used[a] = renumber[a] == 0 ? 1 : 0;
    comm_.sum(used.data(), static_cast<int>(nn));
    for (Index a = 0; a < nn; ++a) renumber[a] = used[a] > 0 ? 0 : -1;
  }
  std::int32_t next = 0;
  for (Index a = 0; a < nn; ++a)
    if (renumber[a] == 0) renumber[a] = next++;
  if (next == nn) return;
  auto compact = [&](auto& v) {
    for (Index a = 0; a < nn; ++a)
      if (renumber[a] >= 0) v[renumber[a]] = v[a];
    v.resize(static_cast<size_t>(next));
  };
  compact(nodes_.x);
  compact(nodes_.v);
  compact(nodes_.f);
  compact(nodes_.mass);
  compact(nodes_.body);
  for (std::int32_t& a : sup_.node) a = renumber[a];
  prev_sup_ = otm::Supports{};
  rebuild_influences();
}

std::vector<double> OtmSolver::lumped_masses() const {
  // m_a = sum_p N_a(x_p) m_p (seed 003 eq. 2.13).
  const auto* mass = points_.real(kMass);
  struct In {
    double N, m;
  };
  struct Acc {
    double m;
  };
  std::vector<Acc> sums;
  otm::fold_nodes<Acc, In>(
      node_fold_scope(), sums, [](Index) { return true; },
      [&](Index i, In& in) {
        in = In{sup_.N[inf_.entry[i]], mass[inf_.owner[i]]};
        return true;
      },
      [](Acc& acc, const In& in) { otm::add_product(acc.m, in.N, in.m); });
  std::vector<double> m(sums.size());
  for (std::size_t a = 0; a < sums.size(); ++a) m[a] = sums[a].m;
  return m;
}

void OtmSolver::keep_region_share() {
  // Several ranks: each keeps the points of its region of a recursive coordinate bisection
  // (points/rcb_partition.hpp), in their seeded order. Any share is correct (a point finds its nodes
  // on its own rank); a compact one keeps the nodes whose sums cross the ranks (reached by several
  // ranks' points, otm/node_sums.hpp) to a thin layer at the cuts.
  if (!comm_.distributed()) return;
  const Index n = points_.size();
  const int me = comm_.rank(), ranks = comm_.size();
  const Index lo = n * me / ranks, hi = n * (me + 1) / ranks;
  RcbPartition rcb(comm_, dim_);
  const std::vector<int> dest = rcb.partition(points_.view(kPosition) + lo, points_.ints(kId) + lo, hi - lo);
  std::vector<int> counts;
  const std::vector<std::int64_t> owner =
      comm_.all_gather(std::vector<std::int64_t>(dest.begin(), dest.end()), counts);
  std::vector<char> keep(static_cast<size_t>(n), 0);
  for (Index p = 0; p < n; ++p) keep[p] = owner[static_cast<size_t>(p)] == me ? 1 : 0;
  pts_.keep_share(comm_, keep);
}

void OtmSolver::rebuild_influences() {
  otm::build_influences(sup_, nodes_.size(), inf_);
  sharing_.update(comm_, inf_, nodes_.size());
}

otm::NodeFoldScope OtmSolver::node_fold_scope() const {
  return otm::NodeFoldScope{&comm_, &inf_, points_.ints(kId), &sharing_, nodes_.size()};
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
  e.contact = k * (wall_work_ + contact_work_);
  e.transfer = k * remap_work_;  // the node re-generations' velocity projection (adaptivity)
  return e;
}

StepLimiter OtmSolver::step_limiter() const {
  // A point whose signal speed is not finite (J beyond its equation of state's limit) collapses
  // every node's bound at once: it is the one to name.
  const StepLimiter fastest = pts_.step_limiter();
  if (!std::isfinite(fastest.wave_speed + fastest.speed)) return fastest;
  const Index nn = static_cast<Index>(omega2_.size());
  if (nn == 0 || nn != nodes_.size()) return fastest;  // no bound computed for these nodes
  Index top = 0;
  for (Index a = 1; a < nn; ++a)
    if (omega2_[a] > omega2_[top]) top = a;
  const auto* mass = points_.real(kMass);
  const auto* x = points_.view(kPosition);
  auto g = [&](Index p, Index k) { return coupling(sup_, k, x[p], axisym_); };
  double best = -1.0;
  Index which = -1;
  for (Index i = inf_.start[top]; i < inf_.start[top + 1]; ++i) {
    const Index kk = inf_.entry[i], p = inf_.owner[i];
    double G = 0.0;
    for (Index k = sup_.offset[p]; k < sup_.offset[p + 1]; ++k) G += g(p, k);
    const double term = mass[p] * G * g(p, kk);
    if (term > best) {
      best = term;
      which = p;
    }
  }
  StepLimiter out;
  if (which >= 0) {
    const double J = det(points_.view(kDeformationGradient)[which]);
    const int m = static_cast<int>(points_.ints(kMaterialIndex)[which]);
    out = {points_.ints(kId)[which], static_cast<int>(points_.ints(kBodyIndex)[which]),
           pts_.materials()[static_cast<size_t>(m)]->wave_speed(points_, which, J), norm(points_.view(kVelocity)[which]),
           J};
  }
  if (!comm_.distributed()) return out;
  comm_.broadcast(&out, sizeof out, comm_.rank_of_max(which >= 0 ? best : -1.0));
  return out;
}

std::string OtmSolver::derived_constants() const {
  return fmt::format(
      "# otm: {} nodes, {} points; beta = gamma / h^2 = {:.6g} 1/m^2; support radius {:.6g} m "
      "({:.3g} h); {:.1f} support nodes per point on average\n",
      nodes_.size(), seeded_points_, sopt_.gamma / (sopt_.h * sopt_.h), otm::support_radius(sopt_),
      otm::support_radius(sopt_) / sopt_.h, support_totals_.mean);
}

std::vector<std::string> OtmSolver::history_columns() const {
  if (contact_) return {"wall_force", "contact_pairs"};
  return {"wall_force"};
}

std::vector<double> OtmSolver::history_values() const {
  if (contact_) return {reporting_scale() * wall_force_, static_cast<double>(contact_pairs_)};
  return {reporting_scale() * wall_force_};
}

std::vector<std::pair<std::string, double>> OtmSolver::result_values() const {
  const EnergyTotals e = energies();
  const Vec3 p0 = reporting_scale() * momentum0_;
  // What deleted points carried off is not a change of the momentum (on_particle_exit: delete).
  const Vec3 carried = delete_exits_ ? e.momentum + e.removed_momentum : e.momentum;
  const SupportTotals& t = support_totals_;
  std::vector<std::pair<std::string, double>> out{{"node_count", static_cast<double>(nodes_.size())},
          {"support_mean", t.mean},
          {"support_max", static_cast<double>(t.max_size)},
          {"lme_max_iterations", static_cast<double>(t.max_iterations)},
          {"lme_max_condition", t.max_condition},
          {"lme_fallbacks", static_cast<double>(t.fallbacks)},
          {"support_retries", static_cast<double>(t.retries)},
          {"lme_failures", 0.0},  // a failed solve stops the run
          {"point_splits", static_cast<double>(splits_)},
          {"node_regenerations", static_cast<double>(regenerations_)},
          {"light_node_steps", static_cast<double>(carried_node_steps_)},
          {"momentum_change_x", axisym_ ? 0.0 : carried[0] - p0[0]},
          {"momentum_change_y", carried[1] - p0[1]},
          {"momentum_change_z", carried[2] - p0[2]}};
  // Inverting increments of stress-free eroded points, discarded (advance; absent: none).
  const std::int64_t frozen = pts_.frozen_increments_discarded();
  if (frozen > 0) out.emplace_back("frozen_increments_discarded", static_cast<double>(frozen));
  return out;
}

std::vector<std::pair<std::string, double>> OtmSolver::timing_values() const {
  // Supports: the search and the LME solves, also those after splits and re-generations
  // (bench/otm_taylor_bench, docs/performance.md).
  return {{"supports", seconds_.supports},       {"assemble", seconds_.assemble},
          {"node_update", seconds_.nodes},       {"point_update", seconds_.points},
          {"material", seconds_.material},       {"adaptivity", seconds_.adapt},
          {"stable_dt", seconds_.stable_dt}};
}

namespace {

std::unique_ptr<Solver> make_otm(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials,
                                const Communicator& comm) {
  return std::make_unique<OtmSolver>(sc, std::move(materials), comm);
}

}  // namespace

}  // namespace ballista

BALLISTA_REGISTER_SOLVER(ballista::SolverFactory{
    .name = "otm",
    .description = "optimal transportation meshfree method with local max-entropy shape functions (Li, Habbal & "
                   "Ortiz 2010; seed 003)",
    .dimensions = {"3d", "plane_strain", "axisymmetric"},
    .section = "otm",
    .params = ballista::otm_params(),
    .create = &ballista::make_otm,
    .distributed = true,
    .element_seeding = true,
    .cut_lattice = true,
    .courant_step = true})
