#pragma once
// The deck's peridynamics.* parameters: their spec list (names, units, defaults, ranges;
// docs/deck.md), the typed values the solver reads once, and the checks of the section against the
// rest of the deck that the specs cannot express, made before anything is seeded.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// The spec of every peridynamics.* key, in the order docs/deck.md lists them.
std::vector<ParamSpec> pd_params();

/// The peridynamics.* section as the solver uses it.
struct PdParams {
  double horizon = 0.0;                    ///< m: delta, given or m (default 3) lattice spacings
  bool lps = false;                        ///< formulation: lps (state-based, lps_pass.hpp; else bond-based)
  bool partial_volumes = true;             ///< volume_correction: partial (else none)
  double thickness = 1.0;                  ///< m, 2D: totals are per this thickness (3D: 1)
  bool lattice_calibration = true;         ///< calibration: lattice (else continuum)
  bool surface_correction = false;         ///< surface_correction: energy (else none)
  /// Pa, micro-plastic bonds' first yield (from flow_stress if given; absent: micro-elastic)
  std::optional<double> yield_stress;
  std::optional<double> critical_stretch;  ///< s00 as given (at most one of it and fracture_energy)
  std::optional<double> fracture_energy;   ///< J/m^2, G0 (neither given: bonds never fail)
  bool bond_law_fracture_work = false;     ///< fracture_work: bond_law (G0 is the bond law's work; else elastic)
  double stretch_alpha = 0.0;              ///< s0 = s00 - alpha s_min
  double stretch_scatter = 0.0;            ///< relative standard deviation of each point's s00
  std::uint64_t scatter_seed = 0;          ///< which draw of the scatter (0: the default one)
  double dt_safety = 0.8;                  ///< fraction of the Silling-Askari stable step
  double fragment_interval = 0.0;          ///< s between fragment snapshots (0: at the end only)
  double fragment_damage_threshold = 2.0;  ///< points with more damage are left out of fragments
  bool contact = true;                     ///< short-range contact forces (contact_list.hpp)
  bool contact_all_pairs = false;          ///< also between bonded points (LAMMPS PERI), not only unbonded
  bool lammps_break = false;               ///< break_rule: lammps (a breaking bond acts once more)
  double contact_skin = 0.5;               ///< contact list skin over the lattice spacing
  int gas_refamily_steps = 0;              ///< steps between renewals of the gas family (0: never)

  /// Bond ends per point of a full family on the lattice of the deck (the memory estimate; fewer
  /// near a surface).
  double full_family_size(const Scenario& sc) const;
};

/// Reads the section (Scenario::solver_params of a peridynamics deck: every key present, the deck
/// reader filled the defaults) and checks it against the rest of the deck before anything is seeded
/// (a family as large as a body would cost its memory first):
/// - the bonds' materials: only a solid's elastic moduli, nothing a bond would drop;
/// - the horizon or m, not both; the horizon at least the lattice spacing, and, when it spans more
///   than ten spacings, at most twice every solid body's largest extent: beyond that every point's
///   family holds the whole body and its bonds cannot localise damage (beyond half of it, a
///   warning: a test body of a few points at m = 3 is legal; the explosive's gas horizon scales
///   with its own lattice);
/// - critical_stretch or fracture_energy, not both; a thickness only in 2D; gas_refamily_steps a
///   whole number.
PdParams read_pd_params(const Scenario& sc);

/// A DeckError at a key of the peridynamics section (what the specs cannot check), at its line.
[[noreturn]] void pd_section_error(const Scenario& sc, const std::string& key, const std::string& message);

}  // namespace ballista
