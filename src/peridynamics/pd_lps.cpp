// The solver's side of the linear peridynamic solid (formulation: lps; the model and its passes in
// lps_pass.hpp, its constants in lps_constants.hpp): the constants per material, the weighted
// volumes, and one evaluation of the forces with the ghosts' force coefficients from their owners.
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/error.hpp"
#include "peridynamics/bond_constants.hpp"
#include "peridynamics/lps_constants.hpp"
#include "peridynamics/lps_pass.hpp"
#include "peridynamics/pd_solver.hpp"

namespace ballista {

void PdSolver::set_lps_constants(const Scenario& sc) {
  const auto& mats = pts_.materials();
  const pd::LatticeMoments m1 =
      pd::calibration_moments(params_.lattice_calibration, delta_, dx_, params_.partial_volumes, dim_);
  const pd::LpsMoments moments = pd::lps_moments(params_.lattice_calibration, delta_, dx_, params_.partial_volumes);
  m1_ = m1.m1;
  lps_bulk_.assign(static_cast<size_t>(nmat_), 0.0);
  lps_shear_.assign(static_cast<size_t>(nmat_), 0.0);
  std::vector<double> c(nmat_, 0.0), s0(nmat_, std::numeric_limits<double>::infinity());
  for (int a = 0; a < nmat_; ++a) {
    if (gas_material_[a]) continue;  // no bonds: its stiffness is its pressure (gas_pass.hpp)
    const ProbedModuli mod = probe_moduli(*mats[a]);
    if (!(mod.bulk > 0.0) || !(mod.shear > 0.0) || !std::isfinite(mod.bulk) || !std::isfinite(mod.shear))
      throw DeckError(sc.file, 0, 0, "materials." + mats[a]->name(),
                      fmt::format("the LPS solid needs positive bulk and shear moduli; material '{}' gives {:g} and "
                                  "{:g} Pa",
                                  mats[a]->name(), mod.bulk, mod.shear));
    lps_bulk_[a] = mod.bulk;
    lps_shear_[a] = mod.shear;
    c[a] = pd::micromodulus(pd::lps_equivalent_bulk(mod.bulk, mod.shear), m1.m1, 3);
    s0[a] = pd::lps_critical_stretch(params_.critical_stretch, params_.fracture_energy, mod.shear, moments);
  }
  pd::PairConstants pairs = pd::pair_constants(c, s0, gas_material_);
  c_ = std::move(pairs.c);
  s00_ = std::move(pairs.s00);
  c_contact_ = std::move(pairs.c_contact);
}

namespace {

pd::LpsPassArgs lps_args(const pd::LocalPoints& local, const pd::BondFamily& bonds, const std::vector<Vec3>& x_prev,
                         const std::vector<double>& inv_len0, const std::vector<std::int32_t>& mirror) {
  pd::LpsPassArgs a{};
  a.x = local.x.empty() ? nullptr : local.x[0].v;
  a.x_prev = x_prev.empty() ? nullptr : x_prev[0].v;
  a.vol0 = local.vol0.data();
  a.material = local.material.data();
  a.length0 = bonds.length0.data();
  a.inv_length0 = inv_len0.data();
  a.beta = bonds.volume_factor.data();
  a.other = bonds.other.data();
  a.mirror = mirror.data();
  a.offset = bonds.offset.data();
  a.ghost = local.ghost.data();
  return a;
}

}  // namespace

void PdSolver::build_lps_weighted_volumes() {
  const pd::LpsPassArgs a = lps_args(local_, bonds_, x_prev_, inv_len0_, mirror_);
  lps_m_.assign(static_cast<size_t>(local_.size()), 0.0);
  pd::lps_weighted_volume(a, 0, local_.bond_local, lps_m_.data());
  halo_.update_bond_values(comm_, local_, lps_m_);  // a ghost's row is partial: its m is its owner's
  pd::LpsPassArgs b = a;
  b.m = lps_m_.data();
  b.shear = lps_shear_.data();
  lps_alpha_.assign(static_cast<size_t>(local_.size()), 0.0);
  pd::lps_deviatoric_stiffness(b, 0, local_.size(), lps_alpha_.data());
}

void PdSolver::lps_pass() {
  const Index n = points_.size(), nl = local_.size();
  // Sized, not cleared: pass 1 writes every own point's values, and a ghost's are read only after
  // its owner's have come (coef every evaluation; coef_old and breaks when a bond broke somewhere).
  // Contact ghosts, appended after the bond points, have no bonds and are never read.
  const auto nls = static_cast<size_t>(nl);
  for (std::vector<double>* v : {&lps_theta_, &lps_theta_old_, &lps_breaks_, &lps_coef_, &lps_coef_old_, &lps_s_,
                                 &lps_s_old_, &lps_m_, &lps_alpha_})
    v->resize(nls, 0.0);
  pd::LpsPassArgs a = lps_args(local_, bonds_, x_prev_, inv_len0_, mirror_);
  a.bulk = lps_bulk_.data();
  a.shear = lps_shear_.data();
  a.m = lps_m_.data();
  a.alpha_point = lps_alpha_.data();
  a.s0 = s0_.data();
  a.alpha = params_.stretch_alpha;
  a.broken = bonds_.broken.data();
  a.contact = params_.contact;
  a.micromodulus = c_.data();
  a.nmat = nmat_;
  a.cs_over_c = 15.0 / delta_;
  a.range = 1.35 * dx_;
  a.plastic = sp_.empty() ? nullptr : sp_.data();
  if (a.plastic) lps_length_.resize(bonds_.other.size());
  a.length = a.plastic ? lps_length_.data() : nullptr;
  if (!sp_.empty()) lps_td_.resize(bonds_.other.size(), 0.0);  // the reference state: t^d = 0
  a.td_prev = lps_td_.empty() ? nullptr : lps_td_.data();
  a.yield_sq = params_.yield_stress ? *params_.yield_stress * *params_.yield_stress : 0.0;
  a.theta = lps_theta_.data();
  a.theta_old = lps_theta_old_.data();
  a.coef = lps_coef_.data();
  a.coef_old = lps_coef_old_.data();
  a.s_elastic = lps_s_.data();
  a.s_elastic_old = lps_s_old_.data();
  a.breaks = lps_breaks_.data();
  Acc& A = acc_;
  a.f = A.f[0].v;
  a.energy = A.energy.data();
  a.dissipated = A.dis.data();
  a.vol_broken = A.vol_broken.data();
  a.smax = A.smx.data();
  a.e_contact = A.e_contact.data();
  a.k_contact = A.k_contact.data();
  const Index* own = local_.own.data();
  for_each(0, n, [&](Index i) { pd::lps_dilatation(a, own[i]); });
  if (a.plastic) for_each(0, n, [&](Index i) { pd::lps_return(a, own[i]); });
  halo_.update_bond_values(comm_, local_, lps_coef_);  // a ghost's B needs its whole row: its owner's
  bool any_break = false;
  for (Index i = 0; i < n && !any_break; ++i) any_break = lps_breaks_[own[i]] != 0.0;
  any_break = comm_.any(any_break);
  a.any_break = any_break;
  if (any_break) {
    halo_.update_bond_values(comm_, local_, lps_coef_old_);
    halo_.update_bond_values(comm_, local_, lps_breaks_);
  }
  for_each(0, n, [&](Index i) { pd::lps_forces(a, own[i]); });
  if (any_break) {
    std::uint8_t* broken = bonds_.broken.data();
    for_each(0, static_cast<Index>(bonds_.broken.size()), [&](Index k) {
      if (broken[k] == pd::kBreaking) broken[k] = 1;
    });
  }
}

}  // namespace ballista
