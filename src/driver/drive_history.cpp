#include "driver/drive_history.hpp"

#include <cmath>

#include "io/history_writer.hpp"

namespace ballista {

std::vector<std::string> drive_history_columns(const std::vector<std::string>& state_names) {
  std::vector<std::string> c = {"step", "t"};
  for (int i = 1; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j) c.push_back("F" + std::to_string(i) + std::to_string(j));
  for (int k = 0; k < 6; ++k) c.push_back(std::string("sigma_") + voigt_name(k));
  for (int k = 0; k < 6; ++k) c.push_back(std::string("sigma_bar_") + voigt_name(k));
  c.insert(c.end(), {"I1", "sqrt_J2", "pressure"});
  c.insert(c.end(), state_names.begin(), state_names.end());
  c.insert(c.end(), {"plastic_work", "plastic_work_total", "internal_energy", "iterations"});
  return c;
}

std::vector<double> drive_history_row(const DriveRecord& r) {
  std::vector<double> v = {static_cast<double>(r.step), r.t};
  for (double x : r.F.a) v.push_back(x);
  for (int k = 0; k < 6; ++k) v.push_back(r.sigma(kVoigtI[k], kVoigtJ[k]));
  for (int k = 0; k < 6; ++k) v.push_back(r.sigma_bar(kVoigtI[k], kVoigtJ[k]));
  const double I1 = trace(r.sigma);
  const Mat3 s = deviator(r.sigma);
  v.push_back(I1);
  v.push_back(std::sqrt(0.5 * ddot(s, s)));  // sqrt(J2), J2 = s:s/2
  v.push_back(-I1 / 3.0 + 0.0);              // P = -I1/3 (CATALOGUE sign convention; + 0: no -0)
  v.insert(v.end(), r.state.begin(), r.state.end());
  v.insert(v.end(), {r.plastic_work, r.plastic_work_total, r.internal_energy, static_cast<double>(r.iterations)});
  return v;
}

void write_drive_history(const std::string& path, const DriveResult& result) {
  HistoryWriter w(path, drive_history_columns(result.state_names));
  for (const auto& r : result.records) w.row(drive_history_row(r));
}

}  // namespace ballista
