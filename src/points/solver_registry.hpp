#pragma once
// Registry of discretisations, like the material registry: each solver registers itself from its
// own file (BALLISTA_REGISTER_SOLVER) with its name (simulation.solver), the dimensions it runs,
// its deck section and that section's parameters. The deck reader, `ballista info` and
// make_solver read the registry, so no other file names a solver.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/communicator.hpp"
#include "core/registry.hpp"
#include "core/solver.hpp"
#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

struct SolverFactory {
  std::string name;                     ///< simulation.solver
  std::string description;              ///< one line with its source
  std::vector<std::string> dimensions;  ///< of "3d", "plane_strain", "axisymmetric"
  std::string section;                  ///< deck section of its parameters (read into Scenario::solver_params)
  std::vector<ParamSpec> params;        ///< the section's keys (units, defaults, ranges, choices)
  /// Builds the solver on `comm` (a solver that does not run distributed is only ever given one rank).
  std::unique_ptr<Solver> (*create)(const Scenario& sc, std::vector<std::unique_ptr<Material>> materials,
                                    const Communicator& comm) = nullptr;
  bool distributed = false;  ///< runs on several MPI ranks
  /// The grid.boundary conditions the solver imposes (a face given another one is a deck error,
  /// never ignored); empty: every condition.
  std::vector<FaceBC> face_conditions = {};
  /// Why the solver imposes no other face condition (the deck error says it).
  std::string face_conditions_note = {};
  /// Runs on a graded grid (grid.refine, geometry/grid_axes.hpp); otherwise refine zones are a
  /// deck error.
  bool graded_grid = false;
  /// Seeds a body on its own lattice (bodies[].point_spacing); otherwise particles_per_cell per
  /// grid cell, and point_spacing is a deck error.
  bool point_spacing = false;
  /// Seeds a mesh body at its elements (bodies[].seeding: elements) and builds its discretisation
  /// on the mesh's vertices; otherwise that seeding is a deck error.
  bool element_seeding = false;
  /// Takes points of unequal volumes off the lattice's sites (bodies[].seeding: cut_lattice);
  /// otherwise that seeding is a deck error.
  bool cut_lattice = false;
  /// Cuts pre-cracks into its bonds (`cracks`); otherwise they are a deck error.
  bool pre_cracks = false;
  /// Has separate grid velocity fields with contact between them (contact.model with several
  /// fields); otherwise a solver brings its own contact.
  bool velocity_fields = false;
  /// Its stable step is simulation.cfl times a Courant bound; otherwise it does not read
  /// simulation.cfl (`ballista info` names the solvers that do).
  bool courant_step = false;
  /// Allocates the box's grid cells (grid.cell_size is a mesh); otherwise the cell size is a
  /// lattice spacing and the box only bounds where points may go, so it may hold far more cells.
  bool background_grid = true;
};

/// Registered solvers by name (core/registry.hpp), filled at static-initialisation time.
using SolverRegistry = Registry<SolverFactory, &SolverFactory::name>;
inline const std::vector<SolverFactory>& solver_registry() { return SolverRegistry::sorted(); }
inline const SolverFactory* find_solver(const std::string& name) { return SolverRegistry::find(name); }

/// An optional word parameter of a solver section whose default is the first choice.
inline ParamSpec word_param(const char* name, const char* description, std::vector<std::string> choices) {
  ParamSpec p{name, "-", description, false, 0};
  p.default_choice = choices.front();
  p.choices = std::move(choices);
  return p;
}

}  // namespace ballista

/// Registers one from its own .cpp: BALLISTA_REGISTER_SOLVER(SolverFactory{...}).
#define BALLISTA_REGISTER_SOLVER(...) BALLISTA_REGISTER(::ballista::SolverRegistry, __VA_ARGS__)
