#pragma once
// Hydrodynamic (strengthless, incompressible, inviscid) jet penetration: Birkhoff et al. as given
// in the thesis seed 000, eq. 3.1-3.4. SI units: densities kg/m^3, lengths m, velocities m/s.
namespace ballista::penetration {

/// Hydrodynamic penetration velocity from eq. 3.1, 1/2 rho_p (V-U)^2 = 1/2 rho_t U^2:
/// U_h = V / (1 + sqrt(rho_t/rho_p)) (thesis §5.2, Fig. 5.12/5.14).
double hydrodynamic_penetration_velocity(double V, double rho_p, double rho_t);

/// Birkhoff depth, eq. 3.2: P = L sqrt(rho_p/rho_t) (the jet of length L is fully consumed).
double birkhoff_depth(double L, double rho_p, double rho_t);

/// Particulated jet penetration velocity from eq. 3.3, lambda rho_avg (V-U)^2 = rho_t U^2:
/// U = V / (1 + sqrt(rho_t / (lambda rho_avg))). lambda in [1, 2] (1 continuous, 2 fully particulated).
double particulated_jet_velocity(double V, double lambda, double rho_avg, double rho_t);

/// Particulated jet depth, eq. 3.4: P = L sqrt(lambda rho_avg / rho_t).
double particulated_jet_depth(double L, double lambda, double rho_avg, double rho_t);

}  // namespace ballista::penetration
