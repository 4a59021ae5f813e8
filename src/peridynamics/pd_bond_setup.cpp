// The bonds of the peridynamic solver set up once, out of its constructor: the moduli a material
// gives a bond (probe_moduli), the pair constants c and critical stretches s00 with their
// calibration (continuum or lattice moments) and the micro-plastic yield stretch, the scatter of
// the critical stretch, the tables of the half-bond force pass, the surface correction, each
// point's stable-step stiffness, and the pre-cracks cut into the bonds.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "geometry/seeding.hpp"
#include "peridynamics/pd_solver.hpp"

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
    s.real("mass")[0] = material.density();
    s.real("volume0")[0] = 1.0;
    s.real("volume")[0] = 1.0;
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

void PdSolver::set_bond_constants(const Scenario& sc) {
  const auto& mats = pts_.materials();
  const bool lattice = params_.lattice_calibration;
  const pd::LatticeMoments moments = pd::lattice_moments(delta_, dx_, params_.partial_volumes, dim_);
  // Continuum moments: 3D m1 = pi delta^4, m2 = pi delta^5/5; 2D (unit thickness) m1 = 2 pi delta^3/3,
  // m2 = delta^4/2 (Ha & Bobaru, Int. J. Fract. 162 (2010) 229: c = 9E/(pi h delta^3) in plane stress).
  const double m1 = lattice ? moments.m1 : (dim_ == 3 ? std::numbers::pi * std::pow(delta_, 4)
                                                      : 2.0 * std::numbers::pi * std::pow(delta_, 3) / 3.0);
  const double m2 = lattice ? moments.m2 : (dim_ == 3 ? std::numbers::pi * std::pow(delta_, 5) / 5.0
                                                      : std::pow(delta_, 4) / 2.0);
  // The dilatational modulus of each material in the model's dimension: K in 3D, the in-plane bulk
  // modulus K2 in 2D (K + G/3 in plane strain, E/(2(1 - nu)) in plane stress).
  std::vector<double> kd(nmat_), c(nmat_), s0(nmat_);
  gas_material_.assign(static_cast<size_t>(nmat_), 0);
  for (int a = 0; a < nmat_; ++a) gas_material_[a] = std::string(mats[a]->model()) == "explosive";
  // Bonds carry the solids' forces: their points keep F = I and zero stress, which the output and
  // the failure diagnostics would show as if they were measured. The gas (an explosive) is fed F
  // and has a pressure, so those two stay when it is present; the rotation, velocity gradient and
  // MPM's particle half-size never mean anything here.
  const bool gas = std::find(gas_material_.begin(), gas_material_.end(), 1) != gas_material_.end();
  for (const char* name : {"R", "L", "half_size"}) points_.set_output(name, false);
  if (!gas)
    for (const char* name : {"F", "stress"}) points_.set_output(name, false);
  if (sc.output.domains)
    throw DeckError(sc.file, 0, 0, "output.domains",
                    "peridynamic points have no deforming domain to draw (their bonds carry no F): set output.domains "
                    "to false");
  // Bodies on their own, coarser lattice (bodies[].point_spacing): only the products. A solid's
  // bonds are calibrated on the lattice of grid.cell_size (lattice_moments); the gas is a pressure
  // whose measure X is a normalised average over whatever family it has, so a coarser gas lattice
  // scales its horizon with its spacing (build_gas_family) and keeps every relation.
  body_scale_.assign(sc.bodies.size(), 1.0);
  for (size_t b = 0; b < sc.bodies.size(); ++b) {
    const BodySpec& body = sc.bodies[b];
    if (!(body.point_spacing > 0.0)) continue;
    auto fail = [&](const std::string& what) {
      throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path + ".point_spacing", what);
    };
    bool gas = false;
    for (int a = 0; a < nmat_; ++a) gas = gas || (mats[a]->name() == body.material && gas_material_[a]);
    if (!gas)
      fail("only an explosive body (the products, a peridynamic gas) may take its own lattice spacing: a solid's "
           "bonds are calibrated on grid.cell_size = " + fmt::format("{:g}", dx_) + " m");
    if (body.point_spacing < dx_ * (1.0 - 1e-12))
      fail(
          fmt::format("expected at least grid.cell_size = {:g} m (the products may be coarser than "
                      "the case, not finer), "
                      "got {:g} m",
                      dx_, body.point_spacing));
    body_scale_[b] = std::max(1.0, body.point_spacing / dx_);
    max_scale_ = std::max(max_scale_, body_scale_[b]);
  }
  for (int a = 0; a < nmat_; ++a) {
    if (gas_material_[a]) continue;  // no bonds: its stiffness is its pressure (gas_pass.hpp)
    const ProbedModuli mod = probe_moduli(*mats[a]);
    if (!(mod.bulk > 0.0) || !std::isfinite(mod.bulk))
      throw DeckError(sc.file, 0, 0, "materials." + mats[a]->name(),
                      fmt::format("peridynamics needs a positive bulk modulus; material '{}' gives {:g} Pa",
                                  mats[a]->name(), mod.bulk));
    kd[a] = mod.bulk;
    if (dim_ == 2) {
      const double E = 9.0 * mod.bulk * mod.shear / (3.0 * mod.bulk + mod.shear);
      const double nu = (3.0 * mod.bulk - 2.0 * mod.shear) / (2.0 * (3.0 * mod.bulk + mod.shear));
      kd[a] = sc.simulation.plane_stress ? E / (2.0 * (1.0 - nu)) : mod.bulk + mod.shear / 3.0;
    }
  }
  m1_ = m1;
  for (int a = 0; a < nmat_; ++a) {
    // continuum: c = 18 K/(pi delta^4) (S&A 2005 eq. 22), s00 = sqrt(5 G0/(9 K delta)) (eq. 25), exact
    // for the integral over the horizon sphere; on the lattice the sums differ (K_PD = 0.90 K and
    // G = 0.87 G0 at m = 3 with partial volumes), so `lattice` takes the same two relations over the
    // lattice family of an interior point: c = 18 K/m1, s00 = sqrt(2 G0/(c m2)) (bond_family.hpp).
    // The energy density of a dilatation eps is W = c eps^2 m1 / 4 for any dimension (S&A 2005 eq. 21
    // summed over the family); it equals the continuum 9 K eps^2/2 in 3D and 2 K2 eps^2 in 2D (eps in
    // both in-plane directions). So c = 18 K/m1 (3D) or 8 K2/m1 (2D). A crack opening through its
    // critical stretch releases G = c s0^2 m2/2, so s00 = sqrt(2 G0/(c m2)) (eq. 25 in 3D with the
    // continuum m2).
    c[a] = (dim_ == 3 ? 18.0 * kd[a] : 8.0 * kd[a]) / m1;
    if (params_.critical_stretch)
      s0[a] = *params_.critical_stretch;
    else if (params_.fracture_energy)
      s0[a] = std::sqrt(2.0 * *params_.fracture_energy / (c[a] * m2));
    else
      s0[a] = kInf;
  }
  // Micro-plastic bonds: first yield of the most stretched bond (the one along the load) under
  // uniaxial stress sigma_y, s_y = sigma_y/E_PD with the modulus of the bond-based model (nu = 1/4 in
  // 3D: E = 3K/2; in 2D E = 4 K2/3 for plane stress, nu = 1/3, and plane strain alike). With several
  // materials the smallest modulus sets it (one yield stretch for every bond).
  if (params_.yield_stress) {
    double e_min = kInf;
    for (int a = 0; a < nmat_; ++a)
      if (!gas_material_[a]) e_min = std::min(e_min, dim_ == 3 ? 1.5 * kd[a] : 4.0 / 3.0 * kd[a]);
    yield_stretch_ = *params_.yield_stress / e_min;
  }
  c_.resize(static_cast<size_t>(nmat_ * nmat_));
  c_contact_.resize(c_.size());
  s00_.resize(c_.size());
  for (int a = 0; a < nmat_; ++a)
    for (int b = 0; b < nmat_; ++b) {
      // A gas takes no bond stiffness, and none in the contact springs either (they scale with c).
      const bool gas = gas_material_[a] || gas_material_[b];
      c_[a * nmat_ + b] = gas ? 0.0 : 2.0 * c[a] * c[b] / (c[a] + c[b]);
      s00_[a * nmat_ + b] = gas ? kInf : std::min(s0[a], s0[b]);
      // Products meeting a solid they were not bonded to (gas streaming towards the case from
      // deep inside the charge) are stopped by the solid's contact springs; gas-gas pairs have none.
      c_contact_[a * nmat_ + b] = gas_material_[a] && gas_material_[b] ? 0.0
                                  : gas_material_[a]                  ? c[b]
                                  : gas_material_[b]                  ? c[a]
                                                                      : c_[a * nmat_ + b];
    }
}

void PdSolver::init_critical_stretch() {
  const Index nl = local_.size(), nb = local_.bond_local;
  s0_.assign(static_cast<size_t>(nl), kInf);
  const auto* mat = local_.material.data();
  for (Index p = 0; p < nb; ++p) {
    double s = kInf;
    for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k)
      s = std::min(s, s00_[mat[p] * nmat_ + mat[bonds_.other[k]]]);
    s0_[p] = s;  // the first step breaks at s00 (no previous stretch yet)
  }
  // Scatter of the critical stretch (stretch_scatter): s00 of each point times 1 + sigma z, z a
  // standard normal drawn from the point's id (splitmix64 + Box-Muller: the same for any thread
  // count, rank count or run), truncated to [1 - 3 sigma, 1 + 3 sigma]. A flawless lattice breaks
  // with its own symmetry (an expanding ring into identical fragments); real materials carry flaws
  // (Grady 2006 ch. 2). The smaller s0 of a bond's two ends still decides.
  if (const double sigma = params_.stretch_scatter; sigma > 0.0) {
    const auto* id = local_.id.data();
    auto mix = [](std::uint64_t z) {
      z += 0x9e3779b97f4a7c15ULL;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      return z ^ (z >> 31);
    };
    for (Index p = 0; p < nb; ++p) {
      const std::uint64_t h1 = mix(static_cast<std::uint64_t>(id[p]) * 2 + 1), h2 = mix(h1);
      const double u1 = (static_cast<double>(h1 >> 11) + 0.5) / 9007199254740992.0;  // (0, 1)
      const double u2 = static_cast<double>(h2 >> 11) / 9007199254740992.0;
      const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
      s0_[p] *= 1.0 + sigma * std::clamp(z, -3.0, 3.0);
    }
  }
  halo_.update_bond_values(comm_, local_, s0_);  // a ghost's row is partial: its s0 is its owner's
  s00_point_ = s0_;
}

void PdSolver::apply_surface_correction() {
  const Index nb = local_.bond_local;
  const auto* vol0 = local_.vol0.data();
  const pd::LatticeMoments moments = pd::lattice_moments(delta_, dx_, params_.partial_volumes, dim_);
  // Surface correction (surface_correction: energy; Madenci & Oterkus 2014 §4.2, reviewed by Le &
  // Bobaru, Comput. Mech. 61 (2018) 499): a point near a free surface misses part of its family and
  // is softer; under a uniform dilatation its energy density is c eps^2 m1_p / 4 instead of the
  // interior c eps^2 m1 / 4, so its factor is lambda_p = m1 / m1_p, and a bond is stiffened by the
  // mean of its two ends' factors (forces and energies; the critical stretch is left as it is).
  if (params_.surface_correction) {
    surface_factor_.assign(static_cast<size_t>(nb), 1.0);
    for_each(0, nb, [&](Index p) {
      double m1p = 0.0;
      for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k)
        m1p += bonds_.length0[k] * bonds_.volume_factor[k] * vol0[bonds_.other[k]];
      if (m1p > 0.0) surface_factor_[p] = moments.m1 / m1p;
    });
    halo_.update_bond_values(comm_, local_, surface_factor_);
  }
}

void PdSolver::set_bond_stiffness() {
  const Index nb = local_.bond_local;
  const auto* vol0 = local_.vol0.data();
  const auto* mat = local_.material.data();
  // Stable step of each point (Silling & Askari 2005 eq. 17): dt < sqrt(2 rho / sum_j V_j c/|xi|).
  for_each(0, nb, [&](Index p) {
    double sum = 0.0;
    for (Index k = bonds_.offset[p]; k < bonds_.offset[p + 1]; ++k) {
      const Index q = bonds_.other[k];
      const double g = surface_factor_.empty() ? 1.0 : 0.5 * (surface_factor_[p] + surface_factor_[q]);
      sum += g * vol0[q] * bonds_.volume_factor[k] * c_[mat[p] * nmat_ + mat[q]] / bonds_.length0[k];
    }
    stiff_bond_[p] = sum;
  });
}

/// What the half-bond force pass needs besides the bonds: each point's damage denominator, where
/// each row's upper part starts, where each bond sits in its other end's row, and the blocks of
/// points (compute_forces).
void PdSolver::build_bond_tables() {
  const Index nb = local_.bond_local;
  const auto* vol0 = local_.vol0.data();
  // The damage denominator of each point, sum_j beta V_j, and for the half-bond force pass (each
  // bond evaluated once, from its lower-index end): where each row's upper part starts, where each
  // bond sits in its other end's row, and the blocks of points (compute_forces).
  vol_all_.assign(static_cast<size_t>(nb), 0.0);
  upper_.assign(static_cast<size_t>(nb), 0);
  mirror_.assign(bonds_.other.size(), 0);
  inv_len0_.resize(bonds_.other.size());
  for_each(0, static_cast<Index>(inv_len0_.size()), [&](Index k) { inv_len0_[k] = 1.0 / bonds_.length0[k]; });
  for_each(0, nb, [&](Index p) {
    double va = 0.0;
    const Index k0 = bonds_.offset[p], k1 = bonds_.offset[p + 1];
    for (Index k = k0; k < k1; ++k) {
      const Index q = bonds_.other[k];
      va += bonds_.volume_factor[k] * vol0[q];
      // Rows are sorted by neighbour index: p's place in q's row by binary search.
      const auto* row = bonds_.other.data() + bonds_.offset[q];
      const auto* end = bonds_.other.data() + bonds_.offset[q + 1];
      mirror_[k] = static_cast<std::int32_t>(std::lower_bound(row, end, static_cast<std::int32_t>(p)) - row);
    }
    vol_all_[p] = va > 0.0 ? va : 1.0;  // a point without bonds has no damage
    upper_[p] = std::upper_bound(bonds_.other.data() + k0, bonds_.other.data() + k1, static_cast<std::int32_t>(p)) -
                bonds_.other.data();
  });
  // Blocks of the half-bond pass over ids: block b holds ids [bB, (b + 1)B), B at least the largest
  // id span of a bond (a bond of block b ends in b or b + 1) and at least 64 blocks when the points
  // allow (so that two phases keep every thread busy). A function of the bonds only, so on several
  // ranks each own point receives its bonds' contributions in the serial order.
  {
    const auto* id = local_.id.data();
    std::int64_t span = 1, top = 0;
    for (Index p = 0; p < nb; ++p) {
      top = std::max(top, id[p] + 1);
      if (bonds_.offset[p + 1] > bonds_.offset[p])
        span = std::max(span, id[bonds_.other[bonds_.offset[p + 1] - 1]] - id[p]);
    }
    span = comm_.max(span);
    top = comm_.max(top);
    const std::int64_t block = std::max<std::int64_t>(span, (global_points_ + 63) / 64);
    block_start_.clear();
    Index l = 0;
    for (std::int64_t b = 0; b < top; b += block) {
      while (l < nb && id[l] < b) ++l;
      block_start_.push_back(l);
    }
    block_start_.push_back(nb);
  }
}

/// Pre-cracks (deck `cracks`): the bonds whose ends lie on either side of each segment.
void PdSolver::cut_pre_cracks(const Scenario& sc) {
  // Pre-cracks (deck `cracks`): bonds whose ends lie on either side of the segment, in the x-y plane.
  const auto* bid = local_.body.data();
  const auto* x0 = local_.x0.data();
  for (const CrackSpec& crack : sc.cracks) {
    const int body = crack.body.empty() ? -1 : body_index(sc, crack.body);
    const Vec3 a = crack.from, b = crack.to;
    // Which side of the line o-e the point c is on, in the x-y plane: +1 left, -1 right, 0 on it
    // (within 1e-9 of the length o-e, so that round-off never decides a point on the line).
    auto side = [](const Vec3& o, const Vec3& e, const Vec3& c) {
      const double len = std::hypot(e[0] - o[0], e[1] - o[1]);
      const double d = ((e[0] - o[0]) * (c[1] - o[1]) - (e[1] - o[1]) * (c[0] - o[0])) / len;
      return std::abs(d) <= 1e-9 * len ? 0 : (d > 0.0 ? 1 : -1);
    };
    const Index cut = cut_bonds([&](Index p, Index q) {
      if (body >= 0 && bid[p] != body) return false;  // bonds join points of one body only
      const Vec3 &xp = x0[p], &xq = x0[q];
      if (xp[0] == xq[0] && xp[1] == xq[1]) return false;  // a bond along z crosses no x-y segment
      // Crossing of the segments p-q and a-b: p and q on either side of the crack line (a point on
      // it counts as left), a and b strictly on either side of the bond's line; both tests read
      // the same from either end, so a bond is cut at both ends or neither.
      const bool pq = (side(a, b, xp) >= 0) != (side(a, b, xq) >= 0);
      return pq && side(xp, xq, a) * side(xp, xq, b) < 0;
    });
    if (cut == 0)
      throw DeckError(crack.mark.file, crack.mark.line, crack.mark.column, crack.mark.key_path,
                      "this crack cuts no bond: check that the segment crosses the body (x-y plane)");
  }
}

}  // namespace ballista
