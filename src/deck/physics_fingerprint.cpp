#include "deck/physics_fingerprint.hpp"

#include <cstdint>
#include <sstream>

#include <fmt/format.h>

namespace ballista {

namespace {

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return {};
  const auto b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

/// Whether a line of the resolved YAML stays out of the fingerprint (physics_fingerprint.hpp).
bool skipped(const std::string& line, const std::string& section, bool with_grid) {
  const std::string t = trimmed(line);
  if (t.empty() || t[0] == '#') return true;
  if ((section == "grid" && !with_grid) || section == "output") return true;
  const auto colon = t.find(':');
  const std::string key = colon == std::string::npos ? std::string() : t.substr(0, colon);
  const std::string value = colon == std::string::npos ? std::string() : trimmed(t.substr(colon + 1));
  const bool second_level = line.rfind("  ", 0) == 0 && line.rfind("   ", 0) != 0;
  if (second_level && section == "simulation" && (key == "end_time" || key == "threads")) return true;
  if (second_level && section == "penetration" &&
      (key == "axis_radius" || key == "stop_tolerance" || key == "convergence_record"))
    return true;
  return value == "none" || value == "~";
}

std::string fingerprint(const std::string& resolved_yaml, bool with_grid) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a offset basis and prime (64 bits)
  std::istringstream in(resolved_yaml);
  std::string line, section;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] != ' ' && line[0] != '#') section = trimmed(line.substr(0, line.find(':')));
    if (skipped(line, section, with_grid)) continue;
    for (const char c : line + "\n") {
      h ^= static_cast<unsigned char>(c);
      h *= 1099511628211ull;
    }
  }
  return fmt::format("{:016x}", h);
}

}  // namespace

std::string physics_fingerprint(const std::string& resolved_yaml) { return fingerprint(resolved_yaml, false); }

std::string configuration_fingerprint(const std::string& resolved_yaml) { return fingerprint(resolved_yaml, true); }

}  // namespace ballista
