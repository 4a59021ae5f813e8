#include "scenario/number_range.hpp"

#include <charconv>
#include <cmath>

namespace ballista {

std::string format_number(double x) {
  if (std::isnan(x)) return ".nan";
  if (std::isinf(x)) return x > 0 ? ".inf" : "-.inf";
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

bool NumberRange::contains(double x) const {
  if (min_exclusive ? !(x > min) : !(x >= min)) return false;
  if (max_exclusive ? !(x < max) : !(x <= max)) return false;
  return true;
}

std::string NumberRange::describe() const {
  const bool lo = std::isfinite(min), hi = std::isfinite(max);
  std::string s;
  if (lo && hi)
    s = "in " + std::string(min_exclusive ? "(" : "[") + format_number(min) + ", " + format_number(max) +
        (max_exclusive ? ")" : "]");
  else if (lo)
    s = std::string(min_exclusive ? "> " : ">= ") + format_number(min);
  else if (hi)
    s = std::string(max_exclusive ? "< " : "<= ") + format_number(max);
  if (!unit.empty() && unit != "1") s += (s.empty() ? "" : " ") + std::string("(") + unit + ")";
  return s;
}

}  // namespace ballista
