#include "scenario/scenario.hpp"

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

}  // namespace ballista
