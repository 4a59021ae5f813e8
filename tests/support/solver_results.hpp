#pragma once
// Test helper: one value of a solver's summary results (Solver::result_values), by name.
#include <string>

#include "core/solver.hpp"

namespace ballista::test {

/// The value named `name` in s.result_values(), or `absent` when the solver does not report it
/// (counters such as frozen_increments_discarded are left out while they are zero).
inline double result_value(const Solver& s, const std::string& name, double absent = 0.0) {
  for (const auto& [k, v] : s.result_values())
    if (k == name) return v;
  return absent;
}

}  // namespace ballista::test
