#include "scenario/scenario.hpp"

#include "core/error.hpp"

namespace ballista {

double LoadCurve::at(double time) const {
  if (t.empty()) return 1.0;
  if (time <= t.front()) return v.front();
  if (time >= t.back()) return v.back();
  size_t k = 1;
  while (t[k] < time) ++k;
  const double s = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return v[k - 1] + s * (v[k] - v[k - 1]);
}

int body_index(const Scenario& sc, const std::string& name) {
  for (size_t b = 0; b < sc.bodies.size(); ++b)
    if (sc.bodies[b].name == name) return static_cast<int>(b);
  return -1;
}

void throw_solver_param_error(const Scenario& sc, const std::string& section, const std::string& key,
                              const std::string& message) {
  const std::string path = key.empty() ? section : section + "." + key;
  const auto it = sc.solver_param_marks.find(key);
  const DeckMark& m = it != sc.solver_param_marks.end() ? it->second : sc.solver_section_mark;
  throw DeckError(m.file.empty() ? sc.file : m.file, m.line, m.column, path, message);
}

}  // namespace ballista
