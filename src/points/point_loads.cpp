#include "points/point_loads.hpp"

namespace ballista {

void PointLoads::compute(const Scenario& sc, const FieldStore& points, double time) {
  fext_.clear();
  ftrac_.clear();
  surface_forces_.clear();
  if (sc.loads.empty()) return;  // no loads: no external-force array, no external work
  if (loads_.empty()) loads_ = make_loads(sc);
  fext_.assign(points.size(), Vec3{});
  LoadForces out{fext_, ftrac_, surface_forces_};
  for (const auto& load : loads_) load->add_forces(points, time, out);
}

std::vector<std::string> PointLoads::history_columns(const Scenario& sc) {
  std::vector<std::string> c;
  for (const auto& load : make_loads(sc))
    for (const std::string& name : load->history_columns()) c.push_back(name);
  return c;
}

std::vector<double> PointLoads::history_values(const Scenario& sc) const {
  if (loads_.empty()) return std::vector<double>(history_columns(sc).size(), 0.0);
  std::vector<double> v;
  for (const auto& load : loads_)
    for (double x : load->history_values()) v.push_back(x);
  return v;
}

}  // namespace ballista
