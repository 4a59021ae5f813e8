#include "penetration/input_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"

namespace ballista::penetration {

void require_finite(const char* model, const char* name, double x, const char* unit) {
  if (!std::isfinite(x)) throw Error(fmt::format("{}: {} = {} must be a finite number [{}]", model, name, x, unit));
}

void require_positive(const char* model, const char* name, double x, const char* unit) {
  if (!(std::isfinite(x) && x > 0)) throw Error(fmt::format("{}: {} = {:g} must be > 0 [{}]", model, name, x, unit));
}

void require_non_negative(const char* model, const char* name, double x, const char* unit) {
  if (!(std::isfinite(x) && x >= 0)) throw Error(fmt::format("{}: {} = {:g} must be >= 0 [{}]", model, name, x, unit));
}

void require_inputs(const char* model, std::initializer_list<InputCheck> inputs) {
  for (const InputCheck& in : inputs) {
    switch (in.range) {
      case InputRange::kPositive:
        require_positive(model, in.name, in.value, in.unit);
        break;
      case InputRange::kNonNegative:
        require_non_negative(model, in.name, in.value, in.unit);
        break;
      case InputRange::kFinite:
        require_finite(model, in.name, in.value, in.unit);
        break;
    }
  }
}

}  // namespace ballista::penetration
