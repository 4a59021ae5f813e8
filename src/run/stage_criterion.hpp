#pragma once
// End criteria of preparation stages (thesis seed 000 §5.1): the overburden stage ends when the
// whole target is within +-5 % of the requested confining stress.
#include <cstdint>
#include <string>

#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Result of one stress-equilibrium check over the particles of a body.
struct EquilibriumCheck {
  bool satisfied = false;     ///< at least stage.fraction of the particles within the tolerance
  double worst = 0.0;         ///< largest relative deviation over particles and components
  std::int64_t worst_id = -1; ///< id of the particle with that deviation
  Mat3 worst_stress;          ///< its Cauchy stress, Pa
  Index particles = 0;        ///< particles of the body checked
  Index inside = 0;           ///< of those, within the tolerance
  double within = 0.0;        ///< fraction of those particles within the tolerance
};

/// Relative deviation of a stress from the requested diagonal stress: the largest over the three
/// normal components of |sigma_ii - s_i| / scale_i, where scale_i = |s_i|, or max_j |s_j| for a
/// component requested as zero (a relative band around zero would be empty). All three zero
/// (an unconfined target) gives 0: there is nothing to relax.
double stress_deviation(const Mat3& stress, const Vec3& requested);

/// Checks every (active) particle of body `body` against stage.stress +- stage.tolerance; satisfied
/// when at least stage.fraction of them are inside.
EquilibriumCheck check_stress_equilibrium(const StageSpec& stage, int body, const FieldStore& points);

/// "particle 17 (stress xx, yy, zz = ... Pa) is 12.3 % from the requested ...": for messages.
std::string describe_equilibrium(const StageSpec& stage, const EquilibriumCheck& check);

}  // namespace ballista
