#pragma once
// Small helpers shared by the pressure-dependent single-element tests (CATALOGUE A3-A5), which
// build their material through MaterialFactory::reduce_geo and read the model's state fields.
#include <string>
#include <vector>

#include "driver/point_driver.hpp"
#include "materials/material.hpp"

namespace ballista {

/// Why A3-A5 do not apply to a model without MaterialFactory::reduce_geo.
inline constexpr const char* kNoGeoHookReason =
    "model has no reduce_geo hook (reduction to linear Drucker-Prager + cap)";

/// Index of state field `name` in the driver's records, or -1 if the model has no such field.
int state_index(const DriveResult& r, const std::string& name);

/// Drives one point through the diagonal F-table rows (t, F11, F22 = F33), `substeps` steps per
/// row (linear interpolation of F, CATALOGUE §A).
DriveResult drive_diagonal(const Material& m, const std::vector<double>& t, const std::vector<double>& F11,
                           const std::vector<double>& F22, int substeps);

/// Drives one point through hydrostatic rows F = lambda I with lambda = exp(ev/3) at the rows.
DriveResult drive_hydrostatic(const Material& m, const std::vector<double>& t, const std::vector<double>& ev,
                              int substeps);

/// The sum over steps of |midpoint increment - ln increment| of one diagonal component of F
/// (Hughes & Winget 1980: the model sees 2 (l - 1)/(l + 1) per step, l = F_{n+1}/F_n, which
/// differs from ln l by (l - 1)^3/12 + ...): how far the model's strain may drift from ln F.
double midpoint_strain_drift(const DriveResult& r, int component);

}  // namespace ballista
