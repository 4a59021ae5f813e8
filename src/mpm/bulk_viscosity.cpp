#include "mpm/bulk_viscosity.hpp"

#include <algorithm>

#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "materials/eos.hpp"
#include "materials/failure.hpp"

namespace ballista {

BulkViscosityPass apply_bulk_viscosity(PointSet& pts, const BulkViscosity& bv, double cell, double dt, bool book_new,
                                       std::vector<double>& c, std::vector<double>& c_reference,
                                       const double* cells, Index begin, Index end) {
  FieldStore& s = pts.store();
  const Index n = s.size();
  if (end < 0) end = n;
  c.resize(static_cast<std::size_t>(n));
  if (bv.reference_sound_speed) c_reference.resize(static_cast<std::size_t>(n));
  // The sound speed of each point at its current J, and whether its model keeps an EOS energy.
  const auto& groups = pts.material_groups();
  const auto& materials = pts.materials();
  std::vector<std::uint8_t> eos_energy(materials.size(), 0), stress_free_failed(materials.size(), 0);
  for (std::size_t m = 0; m < materials.size(); ++m) {
    if (groups[m].empty()) continue;
    const std::span<const Index> in = pts.material_points_in(m, begin, end);
    if (!in.empty()) {
      materials[m]->wave_speeds(s, in.data(), static_cast<Index>(in.size()), c.data());
      if (bv.reference_sound_speed)
        materials[m]->reference_wave_speeds(s, in.data(), static_cast<Index>(in.size()), c_reference.data());
    }
    eos_energy[m] = materials[m]->has_state(kEosEnergyField) ? 1 : 0;
    stress_free_failed[m] = materials[m]->failed_points_are_stress_free() ? 1 : 0;
  }
  const double* failed = s.has(kFailed) ? s.real(kFailed) : nullptr;
  double* q = s.real(kBulkViscosity);
  double* eint = s.real(kInternalEnergy);
  double* E = s.has(kEosEnergy) ? s.real(kEosEnergy) : nullptr;
  const auto* mat = s.ints(kMaterialIndex);
  const auto* mass = s.real(kMass);
  const auto* vol = s.real(kVolume);
  const auto* vol0 = s.real(kReferenceVolume);
  const auto* L = s.view(kVelocityGradient);
  const auto* v = s.view(kVelocity);
  double out[1];
  deterministic_sum<1>(begin, end, [&](Index p, double* o) {
    const double trD = L[p](0, 0) + L[p](1, 1) + L[p](2, 2);
    // Eroded to zero stress (thesis eq. 6.13-6.14): the point carries no pressure, viscous or not.
    const bool stress_free = failed && stress_free_failed[mat[p]] && failed[p] > 0.0;
    const double l = cells ? cells[p] : cell;
    const double c_linear = bv.reference_sound_speed ? c_reference[p] : c[p];
    const double q_new = stress_free ? 0.0 : bulk_viscosity_pressure(bv, mass[p] / vol[p], c_linear, l, trD);
    // Heat = q (-dV): the pressure times the volume the point lost over dt (positive: q acts in
    // compression only), with the volume at the end of the update.
    const double w = (book_new ? q_new : q[p]) * (-trD) * vol[p] * dt;
    eint[p] += w;
    if (E && eos_energy[mat[p]]) E[p] += w / vol0[p];  // per reference volume (eos.hpp)
    q[p] = q_new;
    o[0] += w;
    // The Courant speed with q, + |v|, in place of c; expanding points keep c. Points eroded to
    // zero stress (debris that offers no resistance is squeezed at any rate) carry no wave: |v|
    // alone, as in the step (PointSet::zero_wave_speeds_of_stress_free).
    const double signal = stress_free ? 0.0 : q_new > 0.0 ? bulk_viscosity_signal_speed(bv, c[p], l, trD, c_linear) : c[p];
    c[p] = signal + norm(v[p]);
  }, out);
  double vmax = 0.0, rmax = 0.0;
#pragma omp parallel for reduction(max : vmax, rmax) schedule(static) if (end - begin > kParallelThreshold)
  for (Index p = begin; p < end; ++p) {
    vmax = std::max(vmax, c[p]);
    rmax = std::max(rmax, c[p] / (cells ? cells[p] : cell));
  }
  return {out[0], vmax, rmax};
}

}  // namespace ballista
