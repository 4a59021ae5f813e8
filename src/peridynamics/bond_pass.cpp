#include "peridynamics/bond_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace ballista::pd {

namespace {

// kW bonds of one row at a time (GCC/Clang vector extension: one 512-bit register, or two of 256
// bits, per quantity). A row's bonds end at kW different points, so the lanes' writes to their
// other ends never collide. Every function taking or returning these is internal and inlined, so
// the warning that a 512-bit vector's calling convention differs without AVX-512 does not apply.
#pragma GCC diagnostic ignored "-Wpsabi"
constexpr int kW = 8;  // the broken flags of kW bonds are read as one 64-bit word
typedef double VecW __attribute__((vector_size(kW * sizeof(double))));
typedef long MaskW __attribute__((vector_size(kW * sizeof(long))));

inline VecW splat_w(double v) {
  return VecW{v, v, v, v, v, v, v, v};
}
inline VecW load_w(const double* p) {
  VecW v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

/// Per-point values at the other ends of kW bonds: base[q] and, for 3-vectors, base[3 q + d].
/// AVX-512 has a gather instruction; elsewhere the loads are element by element.
struct OtherEnds {
  const std::int32_t* q;
#if defined(__AVX512F__)
  __m512i q1, q3;
  explicit OtherEnds(const std::int32_t* other) : q(other) {
    q1 = _mm512_maskz_cvtepi32_epi64(0xff,
                                     _mm256_loadu_si256(reinterpret_cast<const __m256i*>(other)));
    q3 = _mm512_add_epi64(q1, _mm512_add_epi64(q1, q1));
  }
  VecW of(const double* base) const {
    return VecW(_mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xff, q1, base, 8));
  }
  VecW of3(const double* base, int d) const {
    return VecW(_mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xff, q3, base + d, 8));
  }
  void set(double* base, const VecW& v) const {
    _mm512_i64scatter_pd(base, q1, __m512d(v), 8);
  }
  void set3(double* base, int d, const VecW& v) const {
    _mm512_i64scatter_pd(base + d, q3, __m512d(v), 8);
  }
#else
  explicit OtherEnds(const std::int32_t* other) : q(other) {}
  VecW of(const double* base) const {
    VecW v;
    for (int l = 0; l < kW; ++l) v[l] = base[q[l]];
    return v;
  }
  VecW of3(const double* base, int d) const {
    VecW v;
    for (int l = 0; l < kW; ++l) v[l] = base[3 * Index{q[l]} + d];
    return v;
  }
  void set(double* base, const VecW& v) const {
    for (int l = 0; l < kW; ++l) base[q[l]] = v[l];
  }
  void set3(double* base, int d, const VecW& v) const {
    for (int l = 0; l < kW; ++l) base[3 * Index{q[l]} + d] = v[l];
  }
#endif
};
inline VecW sqrt_w(const VecW& a) {
  VecW v = a;
  for (int l = 0; l < kW; ++l) v[l] = std::sqrt(v[l]);
  return v;
}
inline bool any_w(const MaskW& m) {
#if defined(__AVX512F__)
  const __m512i v = __m512i(m);
  return _mm512_test_epi64_mask(v, v) != 0;
#else
  long o = 0;
  for (int l = 0; l < kW; ++l) o |= m[l];
  return o != 0;
#endif
}
/// a b + c rounded once, lane by lane (std::fma's result).
inline VecW fma_w(const VecW& a, const VecW& b, const VecW& c) {
#if defined(__AVX512F__)
  return VecW(_mm512_fmadd_pd(__m512d(a), __m512d(b), __m512d(c)));
#else
  VecW r;
  for (int l = 0; l < kW; ++l) r[l] = std::fma(a[l], b[l], c[l]);
  return r;
#endif
}
/// std::max(a, b) lane by lane.
inline VecW max_w(const VecW& a, const VecW& b) {
  return a < b ? b : a;
}

/// The loop, compiled once per combination of the optional models so that the common case (elastic
/// bonds, no surface correction) carries no test for them per bond.
template <bool Plastic, bool Surface>
void bond_pass_t(const BondPassArgs& a, Index p0, Index p1) {
  const double* __restrict x = a.x;
  const double* __restrict vol0 = a.vol0;
  const std::int64_t* __restrict mat = a.material;
  const double* __restrict cmat = a.micromodulus;
  const int nmat = a.nmat;
  const double* __restrict s0 = a.s0;
  const double* __restrict len0 = a.length0;
  const double* __restrict inv_len0 = a.inv_length0;
  const float* __restrict beta = a.beta;
  const std::int32_t* __restrict other = a.other;
  const std::int32_t* __restrict mirror = a.mirror;
  std::uint8_t* __restrict broken = a.broken;
  const Index* __restrict offset = a.offset;
  const Index* __restrict upper = a.upper;
  double* __restrict sp = a.plastic_stretch;
  const double sy = a.yield_stretch, alpha = a.alpha, cs_over_c = a.cs_over_c, range = a.range;
  const bool contact = a.contact, bonded_contact = a.bonded_contact, lammps_break = a.lammps_break;
  const double* __restrict xprev = a.x_prev;
  double* __restrict f = a.f;
  double* __restrict energy = a.energy;
  double* __restrict dis = a.dissipated;
  double* __restrict vb = a.vol_broken;
  double* __restrict smax = a.smax;
  double* __restrict ec = a.e_contact;
  double* __restrict kc = a.k_contact;
  const double* __restrict lambda = a.surface_factor;

  for (Index p = p0; p < p1; ++p) {
    const double xp0 = x[3 * p], xp1 = x[3 * p + 1], xp2 = x[3 * p + 2], vp = vol0[p], s0p = s0[p];
    const double* crow = cmat + mat[p] * nmat;
    // Sums of p's own terms in registers; q's are added in memory.
    double fx = 0.0, fy = 0.0, fz = 0.0, ep = 0.0, smp = smax[p];
    // kW bonds k .. k + kW - 1 at once, when all are intact, stay intact this step and touch no
    // contact (the common case; micro-plastic flow included): the same expressions as `bond`, lane
    // by lane, with the sums to p added lane by lane in the bonds' order, so the results are
    // bitwise those of `bond`. Returns false, having changed nothing, when any of them needs
    // `bond`.
    auto intact_lanes = [&](Index k) -> bool {
      std::uint64_t any_broken;  // kW = 8 flags of one byte
      std::memcpy(&any_broken, broken + k, sizeof any_broken);
      if (any_broken) return false;
      const OtherEnds q(other + k);
      const VecW xq0 = q.of3(x, 0), xq1 = q.of3(x, 1), xq2 = q.of3(x, 2), s0q = q.of(s0);
      const VecW y0 = xq0 - xp0, y1 = xq1 - xp1, y2 = xq2 - xp2;
      const VecW r = sqrt_w(y0 * y0 + y1 * y1 + y2 * y2);
      const VecW r0 = load_w(len0 + k);
      const VecW s = r * load_w(inv_len0 + k) - 1.0;
      // s > min(s0_p, s0_q): the bond breaks (bond()); r = 0: no direction.
      MaskW needs_bond = (s > s0p) | (s > s0q);
      needs_bond |= ~(r > 0.0);  // r = 0, or not finite
      if (bonded_contact) needs_bond |= (r < 0.9 * r0) & (r < range);
      if (any_w(needs_bond)) return false;
      const VecW vq = q.of(vol0);
      const VecW vv = vp * vq;
      VecW bk;
      for (int l = 0; l < kW; ++l) bk[l] = beta[k + l];
      VecW cpq = splat_w(crow[0]);  // one material: no lookup
      if (nmat > 1)
        for (int l = 0; l < kW; ++l) cpq[l] = crow[mat[q.q[l]]];
      if constexpr (Surface) cpq *= 0.5 * (lambda[p] + q.of(lambda));
      VecW se = s;
      if constexpr (Plastic) {
        // Micro-plastic flow as bond() makes it: s_p moves by the excess over +-s_y; the flowing
        // lanes (often all, in a yielding case) write both copies of s_p and their work in order.
        const VecW spk = load_w(sp + k);
        se = s - spk;
        const VecW dsp = se > sy ? se - sy : (se < -sy ? se + sy : splat_w(0.0));
        const MaskW flow = dsp != 0.0;
        if (any_w(flow)) {
          const VecW spn = spk + dsp;
          se -= dsp;  // exact where dsp = 0
          // The work w = wv vv, added with one rounding as bond()'s dis += w compiles (FMA).
          const VecW wv = 0.5 * cpq * sy * (dsp < 0.0 ? -dsp : dsp) * r0 * bk;
          for (int l = 0; l < kW; ++l)
            if (flow[l]) {
              const Index ql = q.q[l];
              sp[k + l] = spn[l];
              sp[offset[ql] + mirror[k + l]] = spn[l];
              dis[p] = std::fma(wv[l], vv[l], dis[p]);
              dis[ql] = std::fma(wv[l], vv[l], dis[ql]);
            }
        }
      }
      const VecW u = 0.5 * cpq * se * se * r0 * bk * vv;
      const VecW G = cpq * se * bk * vv / r;
      // The other ends' sums, all kW at once (they are different points), each the single-rounding
      // FMA that bond() makes.
      q.set3(f, 0, fma_w(-G, y0, q.of3(f, 0)));
      q.set3(f, 1, fma_w(-G, y1, q.of3(f, 1)));
      q.set3(f, 2, fma_w(-G, y2, q.of3(f, 2)));
      q.set(energy, fma_w(splat_w(0.5), u, q.of(energy)));
      if (alpha > 0.0) q.set(smax, max_w(q.of(smax), -alpha * s));
      // p's sums in the bonds' order.
      for (int l = 0; l < kW; ++l) {
        fx = std::fma(G[l], y0[l], fx), fy = std::fma(G[l], y1[l], fy),
        fz = std::fma(G[l], y2[l], fz);
        ep = std::fma(0.5, u[l], ep);
        if (alpha > 0.0) smp = std::max(smp, -alpha * s[l]);
      }
      return true;
    };
    // One bond in full: intact, broken, breaking, plastic, in contact.
    auto bond = [&](Index k) {
      const Index q = other[k];
      const double y0 = x[3 * q] - xp0, y1 = x[3 * q + 1] - xp1, y2 = x[3 * q + 2] - xp2;
      const double r = std::sqrt(y0 * y0 + y1 * y1 + y2 * y2), r0 = len0[k];
      const double vq = vol0[q], vv = vp * vq, bk = beta[k];
      const double c_bond = nmat == 1 ? crow[0] : crow[mat[q]];  // one material: no lookup
      // The bond's micromodulus, with the surface correction's mean factor of its ends if on;
      // contact springs keep the plain c.
      double cpq = c_bond;
      if constexpr (Surface) cpq *= 0.5 * (lambda[p] + lambda[q]);
      // A repulsive contact spring between p and q at r < d (Silling & Askari 2005; LAMMPS PERI):
      // force c_s (d - r) V_p V_q apart; energy c_s V_p V_q (d - r)^2 / 2, half at each end.
      auto repel = [&](double d) {
        const double cs = cs_over_c * c_bond, o = d - r;
        const double e = 0.25 * cs * o * o * vv;
        kc[p] += cs * vq;
        kc[q] += cs * vp;
        if (r > 0.0) {
          const double F = cs * o * vv / r;
          fx -= F * y0, fy -= F * y1, fz -= F * y2;
          f[3 * q] += F * y0, f[3 * q + 1] += F * y1, f[3 * q + 2] += F * y2;
        }
        ec[p] += e;
        ec[q] += e;
      };
      if (broken[k]) {
        vb[p] += bk * vq;
        vb[q] += bk * vp;
        // The ends of a broken bond meet again through contact only.
        if (contact && r < std::min(0.9 * r0, range)) repel(std::min(0.9 * r0, range));
        return;
      }
      const double s = r * inv_len0[k] - 1.0;  // (r - r0)/r0 without a division
      // Micro-plastic bond (seed 001 "Micro-Elastic and -Plastic Materials"; Silling & Askari 2005):
      // elastic in s - s_p up to the yield stretch s_y, perfectly plastic beyond, elastic unloading
      // with s_p kept; plastic work c s_y |ds_p| |xi| beta V_p V_q, half to each end. Failure on s.
      double se = s;
      if constexpr (Plastic) {
        se = s - sp[k];
        double dsp = 0.0;
        if (se > sy) dsp = se - sy;
        else if (se < -sy) dsp = se + sy;
        if (dsp != 0.0) {
          sp[k] += dsp;
          // Both ends' copies (read from the lower end; a checkpoint or a ghost row needs either).
          sp[offset[q] + mirror[k]] = sp[k];
          se -= dsp;
          const double w = 0.5 * cpq * sy * std::abs(dsp) * r0 * bk * vv;
          dis[p] += w;
          dis[q] += w;
        }
      }
      // Bond energy c se^2 |xi| beta V_p V_q / 2 (Silling & Askari 2005 eq. 21, both ends' halves).
      const double u = 0.5 * cpq * se * se * r0 * bk * vv;
      if (s > std::min(s0p, s0[q])) {
        // Failure against the previous step's s0 (LAMMPS PERI's rule), for both ends at once.
        broken[k] = 1;
        broken[offset[q] + mirror[k]] = 1;
        vb[p] += bk * vq;
        vb[q] += bk * vp;
        if (lammps_break) {
          // break_rule: lammps. The bond still acts this step (LAMMPS applies the force, then
          // breaks), and its energy U(s_n+1) is what it dissipates; the next step's first half-kick
          // then carries a force whose energy is gone (LAMMPS's own O(dt) error, kept for parity).
          dis[p] += 0.5 * u;
          dis[q] += 0.5 * u;
          if (r > 0.0) {
            const double G = cpq * se * bk * vv / r;
            fx += G * y0, fy += G * y1, fz += G * y2;
            f[3 * q] -= G * y0, f[3 * q + 1] -= G * y1, f[3 * q + 2] -= G * y2;
          }
          if (alpha > 0.0) {
            smp = std::max(smp, -alpha * s);
            smax[q] = std::max(smax[q], -alpha * s);
          }
          return;
        }
        // Default: from now on the bond exerts no force. It dissipates what the step took out of
        // the motion: velocity Verlet gave the points only the first half-kick of this bond, so the
        // energy booked is U(s_n+1) - 1/2 F (r_n+1 - r_n), the trapezoidal work of the bond over the
        // step; U(s_n+1) alone creates the missing half-kick (+7 % of the energy in a dynamic tear,
        // docs/validation.md). Half to each end.
        const double dp0 = xprev[3 * q] - xprev[3 * p], dp1 = xprev[3 * q + 1] - xprev[3 * p + 1],
                     dp2 = xprev[3 * q + 2] - xprev[3 * p + 2];
        const double r_prev = std::sqrt(dp0 * dp0 + dp1 * dp1 + dp2 * dp2);
        const double F = cpq * se * bk * vv;  // N
        const double d = 0.5 * (u - 0.5 * F * (r - r_prev));
        dis[p] += d;
        dis[q] += d;
        return;
      }
      // f = c s (y/|y|) per unit volume of each end (seed 001 "Microelastic material"), times V_p V_q.
      if (r > 0.0) {
        const double G = cpq * se * bk * vv / r;  // the one division per bond
        fx += G * y0, fy += G * y1, fz += G * y2;
        f[3 * q] -= G * y0, f[3 * q + 1] -= G * y1, f[3 * q + 2] -= G * y2;
      }
      ep += 0.5 * u;
      energy[q] += 0.5 * u;
      if (alpha > 0.0) {  // s0_new = s00 - alpha s_min (LAMMPS PERI); unused with alpha = 0
        smp = std::max(smp, -alpha * s);
        smax[q] = std::max(smax[q], -alpha * s);
      }
      if (bonded_contact && r < std::min(0.9 * r0, range)) repel(std::min(0.9 * r0, range));
    };
    Index k = upper[p];
    const Index kend = offset[p + 1];
    for (; k + kW <= kend; k += kW)
      if (!intact_lanes(k))
        for (Index j = k; j < k + kW; ++j) bond(j);
    for (; k < kend; ++k) bond(k);
    f[3 * p] += fx, f[3 * p + 1] += fy, f[3 * p + 2] += fz;
    energy[p] += ep;
    smax[p] = smp;
  }
}

}  // namespace

void bond_pass(const BondPassArgs& a, Index p0, Index p1) {
  const bool plastic = a.plastic_stretch != nullptr, surface = a.surface_factor != nullptr;
  if (plastic && surface) bond_pass_t<true, true>(a, p0, p1);
  else if (plastic) bond_pass_t<true, false>(a, p0, p1);
  else if (surface) bond_pass_t<false, true>(a, p0, p1);
  else bond_pass_t<false, false>(a, p0, p1);
}

}  // namespace ballista::pd
