// The bonds of the peridynamic solver set up once, out of its constructor: which materials are a
// gas and which bodies take their own lattice, the constants per material pair (the formulas in
// bond_constants.hpp), the scatter of the critical stretch, the tables of the half-bond force pass,
// the surface correction, each point's stable-step stiffness, and the pre-cracks cut into the bonds.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "peridynamics/bond_constants.hpp"
#include "peridynamics/pd_solver.hpp"

namespace ballista {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

void PdSolver::classify_materials(const Scenario& sc) {
  const auto& mats = pts_.materials();
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
}

void PdSolver::read_body_scales(const Scenario& sc) {
  // Bodies on their own, coarser lattice (bodies[].point_spacing): only the products. A solid's
  // bonds are calibrated on the lattice of grid.cell_size (lattice_moments); the gas is a pressure
  // whose measure X is a normalised average over whatever family it has, so a coarser gas lattice
  // scales its horizon with its spacing (build_gas_family) and keeps every relation.
  const auto& mats = pts_.materials();
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
}

void PdSolver::set_bond_constants(const Scenario& sc) {
  if (params_.lps) return set_lps_constants(sc);
  const auto& mats = pts_.materials();
  const pd::LatticeMoments m =
      pd::calibration_moments(params_.lattice_calibration, delta_, dx_, params_.partial_volumes, dim_);
  std::vector<double> kd(nmat_), c(nmat_), s0(nmat_);
  for (int a = 0; a < nmat_; ++a) {
    if (gas_material_[a]) continue;  // no bonds: its stiffness is its pressure (gas_pass.hpp)
    const ProbedModuli mod = probe_moduli(*mats[a]);
    if (!(mod.bulk > 0.0) || !std::isfinite(mod.bulk))
      throw DeckError(sc.file, 0, 0, "materials." + mats[a]->name(),
                      fmt::format("peridynamics needs a positive bulk modulus; material '{}' gives {:g} Pa",
                                  mats[a]->name(), mod.bulk));
    kd[a] = pd::dilatational_modulus(mod, dim_, sc.simulation.plane_stress);
  }
  m1_ = m.m1;
  if (params_.yield_stress) yield_stretch_ = pd::yield_stretch(*params_.yield_stress, kd, gas_material_, dim_);
  // fracture_work: bond_law takes the micro-plastic bonds' own work to break; elastic, the PMB one.
  const double sy = params_.bond_law_fracture_work ? yield_stretch_ : std::numeric_limits<double>::infinity();
  for (int a = 0; a < nmat_; ++a) {
    c[a] = pd::micromodulus(kd[a], m.m1, dim_);  // 0 for a gas (kd 0)
    s0[a] = pd::critical_stretch(params_.critical_stretch, params_.fracture_energy, c[a], m.m2, sy);
  }
  pd::PairConstants pairs = pd::pair_constants(c, s0, gas_material_);
  c_ = std::move(pairs.c);
  s00_ = std::move(pairs.s00);
  c_contact_ = std::move(pairs.c_contact);
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
  // (Grady 2006 ch. 2). The smaller s0 of a bond's two ends still decides. scatter_seed picks
  // another draw (it enters the hash; 0 leaves the default draw's bits unchanged).
  if (const double sigma = params_.stretch_scatter; sigma > 0.0) {
    const auto* id = local_.id.data();
    const std::uint64_t salt = params_.scatter_seed * 0xd1b54a32d192ed03ULL;
    auto mix = [](std::uint64_t z) {
      z += 0x9e3779b97f4a7c15ULL;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      return z ^ (z >> 31);
    };
    for (Index p = 0; p < nb; ++p) {
      const std::uint64_t h1 = mix((static_cast<std::uint64_t>(id[p]) * 2 + 1) ^ salt), h2 = mix(h1);
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
  if (!params_.surface_correction) return;
  // The interior m1 on the lattice whatever the calibration: each point's own m1_p is a lattice sum.
  const pd::LatticeMoments moments = pd::lattice_moments(delta_, dx_, params_.partial_volumes, dim_);
  surface_factor_ = pd::surface_factors(bonds_, local_.bond_local, local_.vol0.data(), moments.m1);
  halo_.update_bond_values(comm_, local_, surface_factor_);
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
