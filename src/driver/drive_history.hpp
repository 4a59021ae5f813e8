#pragma once
// Columns of a driven point's history (history.csv of `ballista drive`): one row per record of
// drive_point. Invariants of the spatial Cauchy stress, tension positive (CATALOGUE sign
// convention): I1 = tr sigma, sqrt(J2) with J2 = s:s/2 (s the deviator), pressure P = -I1/3.
#include <string>
#include <vector>

#include "driver/point_driver.hpp"

namespace ballista {

/// step, t, F11..F33 (row-major), sigma_11 sigma_22 sigma_33 sigma_23 sigma_13 sigma_12 (spatial,
/// Pa), sigma_bar_11 .. sigma_bar_12 (unrotated R^T sigma R, Pa), I1, sqrt_J2, pressure (Pa), the
/// model's state fields (by name), plastic_work (over the step, J/m^3), plastic_work_total and
/// internal_energy (accumulated, J per m^3 of reference volume), iterations (stress control).
std::vector<std::string> drive_history_columns(const std::vector<std::string>& state_names);

/// The values of one record in the order of drive_history_columns.
std::vector<double> drive_history_row(const DriveRecord& r);

/// Writes every record of `result` to `path` as CSV (io/history_writer: shortest round-trip
/// numbers, so full precision). Throws Error if the file cannot be written.
void write_drive_history(const std::string& path, const DriveResult& result);

}  // namespace ballista
