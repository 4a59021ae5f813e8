#pragma once
// The energy audit's terms as history.csv and summary.json name them: one table, so that a new
// term of EnergyTotals is one line here and reaches every list of them.
#include <array>

#include "core/solver.hpp"

namespace ballista {

/// One column of the energy audit. `value` reads it from the totals; the drift (a property of
/// the run, not of one state) is passed in by the caller.
struct EnergyTerm {
  const char* column;       ///< history.csv column (SI: J, kg or kg m/s)
  const char* summary_key;  ///< key in summary.json "energy"; nullptr: history.csv only
  double (*value)(const EnergyTotals& e, double drift);
};

/// In history.csv's column order (after time, step, dt). total() is the balance of
/// EnergyTotals; energy_drift its change over the largest energy scale seen (run loop).
inline constexpr std::array<EnergyTerm, 21> kEnergyTerms = {{
    {"kinetic_energy", "kinetic", [](const EnergyTotals& e, double) { return e.kinetic; }},
    {"internal_energy", "internal", [](const EnergyTotals& e, double) { return e.internal; }},
    {"plastic_work", "plastic_work", [](const EnergyTotals& e, double) { return e.plastic; }},
    {"external_work", "external_work", [](const EnergyTotals& e, double) { return e.external; }},
    {"total_energy", "total", [](const EnergyTotals& e, double) { return e.total(); }},
    {"energy_drift", nullptr, [](const EnergyTotals&, double drift) { return drift; }},
    {"mass", "mass", [](const EnergyTotals& e, double) { return e.mass; }},
    {"momentum_x", nullptr, [](const EnergyTotals& e, double) { return e.momentum[0]; }},
    {"momentum_y", nullptr, [](const EnergyTotals& e, double) { return e.momentum[1]; }},
    {"momentum_z", nullptr, [](const EnergyTotals& e, double) { return e.momentum[2]; }},
    {"removed_mass", "removed_mass", [](const EnergyTotals& e, double) { return e.removed_mass; }},
    {"removed_energy", "removed_energy", [](const EnergyTotals& e, double) { return e.removed_energy; }},
    {"inserted_energy", "inserted_energy", [](const EnergyTotals& e, double) { return e.inserted_energy; }},
    {"damping_work", "damping_work", [](const EnergyTotals& e, double) { return e.damping; }},
    {"contact_work", "contact_work", [](const EnergyTotals& e, double) { return e.contact; }},
    {"friction_work", "friction_work", [](const EnergyTotals& e, double) { return e.friction; }},
    {"transfer_work", "transfer_work", [](const EnergyTotals& e, double) { return e.transfer; }},
    {"eroded_internal_energy", "eroded_internal_energy", [](const EnergyTotals& e, double) { return e.eroded; }},
    {"chemical_energy", "chemical_energy", [](const EnergyTotals& e, double) { return e.chemical; }},
    {"boundary_work", "boundary_work", [](const EnergyTotals& e, double) { return e.boundary; }},
    {"viscous_work", "viscous_work", [](const EnergyTotals& e, double) { return e.viscous; }},
}};

}  // namespace ballista
