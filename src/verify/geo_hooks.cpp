#include "verify/geo_hooks.hpp"

#include <cmath>

namespace ballista {

int state_index(const DriveResult& r, const std::string& name) {
  for (size_t k = 0; k < r.state_names.size(); ++k)
    if (r.state_names[k] == name) return static_cast<int>(k);
  return -1;
}

DriveResult drive_diagonal(const Material& m, const std::vector<double>& t, const std::vector<double>& F11,
                           const std::vector<double>& F22, int substeps) {
  DriveProgram prog;
  for (size_t k = 0; k < t.size(); ++k) {
    FTableRow row;
    row.t = t[k];
    row.F = Mat3::diag(F11[k], F22[k], F22[k]);
    prog.table.push_back(row);
  }
  prog.substeps = substeps;
  return drive_point(m, prog);
}

DriveResult drive_hydrostatic(const Material& m, const std::vector<double>& t, const std::vector<double>& ev,
                              int substeps) {
  std::vector<double> lambda;
  for (double e : ev) lambda.push_back(std::exp(e / 3.0));
  return drive_diagonal(m, t, lambda, lambda, substeps);
}

double midpoint_strain_drift(const DriveResult& r, int c) {
  double d = 0.0;
  for (size_t k = 1; k < r.records.size(); ++k) {
    const double x = r.records[k].F(c, c) / r.records[k - 1].F(c, c) - 1.0;
    d += std::abs(x / (1.0 + 0.5 * x) - std::log1p(x));
  }
  return d;
}

}  // namespace ballista
