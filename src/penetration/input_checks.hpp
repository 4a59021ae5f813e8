#pragma once
// Range checks of the analytic models' inputs. Each throws ballista::Error naming the model, the
// input, its value and its unit ("tate: V = -1 must be > 0 [m/s]"), so every model reports a bad
// argument alike and the command line (`ballista models`) shows the message as it is.
#include <initializer_list>

namespace ballista::penetration {

/// Throws ballista::Error "<model>: <name> = <value> must be > 0 [unit]" unless x > 0 (finite).
void require_positive(const char* model, const char* name, double x, const char* unit);
/// Throws unless x >= 0 (finite).
void require_non_negative(const char* model, const char* name, double x, const char* unit);
/// Throws unless x is finite.
void require_finite(const char* model, const char* name, double x, const char* unit);

/// The range one input must lie in: the require_ check it gets.
enum class InputRange { kPositive, kNonNegative, kFinite };

/// One input of a model with its unit and range: an entry of the list require_inputs checks.
struct InputCheck {
  const char* name;
  double value;
  const char* unit;
  InputRange range;
};

inline InputCheck positive(const char* name, double x, const char* unit) {
  return {name, x, unit, InputRange::kPositive};
}
inline InputCheck non_negative(const char* name, double x, const char* unit) {
  return {name, x, unit, InputRange::kNonNegative};
}
inline InputCheck finite(const char* name, double x, const char* unit) {
  return {name, x, unit, InputRange::kFinite};
}

/// Checks a model's inputs in the order listed, the first out of its range throwing as its
/// require_ check does: a model states the ranges of its inputs once, as one list.
void require_inputs(const char* model, std::initializer_list<InputCheck> inputs);

}  // namespace ballista::penetration
