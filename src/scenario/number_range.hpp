#pragma once
// The allowed range of a number read from a deck, and how a deck prints numbers: shared by the
// deck reader and the kinds that read their own entries (loads) below it.
#include <limits>
#include <string>
#include <utility>

namespace ballista {

/// Shortest text that reads back as exactly `x` (0.3, 8e-05, 1.17e+11); ".inf"/".nan" in YAML style.
std::string format_number(double x);

/// Allowed values of a number; unit is shown in messages ("" or "1" = dimensionless).
struct NumberRange {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  std::string unit;

  bool contains(double x) const;
  /// "> 0 kg/m^3", "in (-1, 0.5)", "" for an unbounded range.
  std::string describe() const;

  static NumberRange any(std::string unit = "") { return {.unit = std::move(unit)}; }
  static NumberRange positive(std::string unit = "") {
    return {.min = 0.0, .min_exclusive = true, .unit = std::move(unit)};
  }
  static NumberRange non_negative(std::string unit = "") { return {.min = 0.0, .unit = std::move(unit)}; }
  /// [lo, hi] with optional exclusive ends.
  static NumberRange between(double lo, double hi, bool lo_exclusive = false, bool hi_exclusive = false,
                             std::string unit = "") {
    return {lo, hi, lo_exclusive, hi_exclusive, std::move(unit)};
  }
};

}  // namespace ballista
