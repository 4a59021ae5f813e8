// Exact piecewise solution of uniaxial strain for J2 plasticity (see uniaxial_strain_j2.hpp for
// the equations and their sources).
#include "verify/uniaxial_strain_j2.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace ballista {

UniaxialStrainJ2::UniaxialStrainJ2(const J2UniaxialParams& p) : p_(p) {
  if (!(p.shear > 0.0) || !(p.yield > 0.0) || !(p.h_iso >= 0.0) || !(p.h_kin >= 0.0))
    throw Error("UniaxialStrainJ2: need shear > 0, yield > 0, h_iso >= 0, h_kin >= 0");
}

void UniaxialStrainJ2::advance_to(double e_new) {
  const double de = e_new - e_;
  if (de == 0.0) return;
  const int dir = de > 0.0 ? 1 : -1;
  const double G = p_.shear;
  // Elastic part: q moves by 2G de until n (q - beta) = r with n = dir (the yield surface in the
  // direction of loading). The strain it takes, clamped to [0, |de|] against round-off when the
  // state starts on the surface.
  const double r = radius();
  const double to_surface = (dir * r + beta_ - q_) / (2.0 * G);  // signed, same sign as de if inside
  const double de_el = dir * std::clamp(dir * to_surface, 0.0, std::abs(de));
  const double de_pl = de - de_el;
  const bool continuing = plastic_ && dir == last_dir_;
  if (de_pl == 0.0) {
    q_ += 2.0 * G * de;
    plastic_ = false;
  } else {
    // On the surface at the event: q = beta + dir r exactly (removes the round-off of q + 2G de_el).
    q_ = beta_ + dir * r;
    if (!continuing) {
      const double e_ev = e_ + de_el;
      events_.push_back({e_ev, p_.bulk * e_ev + 2.0 * q_ / 3.0, p_.bulk * e_ev - q_ / 3.0, q_, beta_, r});
    }
    // Plastic part (consistency): d eps_p = 2G |de| / (3G + H_iso + H_kin).
    const double H = p_.h_iso + p_.h_kin;
    const double dp = 2.0 * G * std::abs(de_pl) / (3.0 * G + H);
    q_ += dir * H * dp;
    beta_ += dir * p_.h_kin * dp;
    eqps_ += dp;
    plastic_ = true;
  }
  e_ = e_new;
  last_dir_ = dir;
}

UniaxialStrainSeries uniaxial_strain_j2_series(const J2UniaxialParams& p, const std::vector<double>& e) {
  UniaxialStrainJ2 m(p);
  UniaxialStrainSeries s;
  for (double x : e) {
    m.advance_to(x);
    s.e.push_back(x);
    s.sigma11.push_back(m.sigma11());
    s.sigma22.push_back(m.sigma22());
    s.q.push_back(m.q());
    s.pressure.push_back(m.pressure());
    s.eqps.push_back(m.eqps());
    s.beta.push_back(m.beta());
    s.radius.push_back(m.radius());
  }
  s.events = m.yield_events();
  return s;
}

}  // namespace ballista
