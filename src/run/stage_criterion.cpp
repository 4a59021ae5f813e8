#include "run/stage_criterion.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/point_fields.hpp"

namespace ballista {

double stress_deviation(const Mat3& s, const Vec3& req) {
  const double big = std::max({std::abs(req[0]), std::abs(req[1]), std::abs(req[2])});
  if (big == 0.0) return 0.0;  // nothing requested (an unconfined target): nothing to relax
  double worst = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double scale = req[i] != 0.0 ? std::abs(req[i]) : big;
    worst = std::max(worst, std::abs(s(i, i) - req[i]) / scale);
  }
  return worst;
}

EquilibriumCheck check_stress_equilibrium(const StageSpec& st, int body, const FieldStore& pts) {
  EquilibriumCheck c;
  const auto* bid = pts.ints(kBodyIndex);
  const auto* id = pts.ints(kId);
  const auto* stress = pts.view(kStress);
  Index inside = 0;
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != body) continue;
    ++c.particles;
    const double d = stress_deviation(stress[p], st.stress);
    if (d <= st.tolerance) ++inside;
    if (d > c.worst || c.worst_id < 0) {
      c.worst = d;
      c.worst_id = id[p];
      c.worst_stress = stress[p];
    }
  }
  c.within = c.particles > 0 ? static_cast<double>(inside) / c.particles : 0.0;
  c.inside = inside;
  // All particles by default (thesis §5.1: "the entire target"); `fraction` < 1 lets a few
  // particles at the corners of the loaded surfaces, where the tractions meet, stay outside.
  c.satisfied = c.particles > 0 && static_cast<double>(inside) >= st.fraction * static_cast<double>(c.particles);
  return c;
}

std::string describe_equilibrium(const StageSpec& st, const EquilibriumCheck& c) {
  if (c.particles == 0) return fmt::format("body '{}' has no active particles", st.body);
  return fmt::format(
      "{} of the {} particles of body '{}' ({:.2f} %) are within {:.1f} % of the requested stress [{:.4g}, {:.4g}, "
      "{:.4g}] Pa; the worst, particle {}, has [{:.4g}, {:.4g}, {:.4g}] Pa ({:.1f} % off)",
      c.inside, c.particles, st.body, 100.0 * c.within, 100.0 * st.tolerance, st.stress[0], st.stress[1], st.stress[2],
      c.worst_id, c.worst_stress(0, 0), c.worst_stress(1, 1), c.worst_stress(2, 2), 100.0 * c.worst);
}

}  // namespace ballista
