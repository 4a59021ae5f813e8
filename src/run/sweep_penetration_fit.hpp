#pragma once
// The impact-velocity study of a sweep (thesis seed 000 §5.2, eq. 5.2-5.5, Figs. 5.11-5.12): when
// every completed run's summary.json has penetration.impact_velocity V and penetration.steady_rate
// U, fits U = a + b V (Orphal & Anderson), evaluates R - Y at each V (eq. 5.3), the extremum V_m
// (eq. 5.4) and the curvature (eq. 5.5), writes SWEEP_DIR/sweep_penetration.json and draws
// penetration_u_vs_v.png and penetration_u_over_uh.png with tools/plot_sweep_penetration.py.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/summary_writer.hpp"
#include "penetration/orphal_anderson.hpp"
#include "run/sweep.hpp"
#include "run/sweep_table.hpp"

namespace ballista {

/// One completed run of the study. Density-dependent values are empty when the summary lacks
/// penetration.penetrator_density or penetration.target_density.
struct SweepPenetrationPoint {
  int run = 0;                         ///< run number k
  double V = 0;                        ///< impact velocity [m/s]
  double U = 0;                        ///< steady penetration rate [m/s]
  std::optional<double> rho_p, rho_t;  ///< penetrator, target density [kg/m^3]
  std::optional<double> U_h;           ///< hydrodynamic rate V / (1 + sqrt(rho_t/rho_p)) [m/s] (eq. 3.1)
  std::optional<double> R_minus_Y;     ///< eq. 5.3 with the fitted a, b [Pa]
};

struct SweepPenetrationFit {
  penetration::LinearFit fit;  ///< U = a + b V, eq. 5.2
  std::vector<SweepPenetrationPoint> points;
  std::optional<double> rho_p, rho_t;        ///< the densities if every run has the same ones
  std::optional<double> curvature;           ///< d^2(R-Y)/dV^2, eq. 5.5 [kg/m^3] (common densities)
  std::optional<double> extremum_velocity;   ///< V_m, eq. 5.4 [m/s] (none when eq. 5.5 is zero)
  std::optional<double> hydrodynamic_slope;  ///< b making eq. 5.5 zero, 1/(1+sqrt(rho_t/rho_p))
};

/// The fit of a table, or nothing when the table is not an impact-velocity study: no completed
/// run, a completed run without penetration.impact_velocity or penetration.steady_rate, or fewer
/// than two distinct velocities.
std::optional<SweepPenetrationFit> sweep_penetration_fit(const SweepTable& table);

/// {"a", "b", "r2", "penetrator_density", "target_density", "curvature", "extremum_velocity",
///  "hydrodynamic_slope", "runs": [{"run", "V", "U", "U_h", "U_over_Uh", "R_minus_Y"}]}, SI units,
/// missing values as null.
JsonValue sweep_penetration_json(const SweepPenetrationFit& f);

/// Writes out_dir/sweep_penetration.json if the table is a study (returns false and writes
/// nothing otherwise).
bool write_sweep_penetration(const SweepTable& table, const std::filesystem::path& out_dir);

/// The post step of `ballista sweep`: write_sweep_penetration, then the plots; a plot failure is
/// printed to stderr as a warning (the sweep still succeeds).
SweepPostStep sweep_penetration_post_step();

}  // namespace ballista
