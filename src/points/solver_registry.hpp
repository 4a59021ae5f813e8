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
  /// Its stable step is simulation.cfl times a Courant bound; otherwise it does not read
  /// simulation.cfl (`ballista info` names the solvers that do).
  bool courant_step = false;
};

/// An optional word parameter of a solver section whose default is the first choice.
inline ParamSpec word_param(const char* name, const char* description, std::vector<std::string> choices) {
  ParamSpec p{name, "-", description, false, 0};
  p.default_choice = choices.front();
  p.choices = std::move(choices);
  return p;
}

/// Registered solvers in name order, filled at static-initialisation time.
const std::vector<SolverFactory>& solver_registry();
const SolverFactory* find_solver(const std::string& name);
bool register_solver(SolverFactory factory);

}  // namespace ballista

#define BALLISTA_SOLVER_CONCAT_(a, b) a##b
#define BALLISTA_SOLVER_CONCAT(a, b) BALLISTA_SOLVER_CONCAT_(a, b)
/// Registers a solver from its own .cpp: BALLISTA_REGISTER_SOLVER(SolverFactory{...}).
#define BALLISTA_REGISTER_SOLVER(...)                                                          \
  namespace {                                                                                  \
  [[maybe_unused]] const bool BALLISTA_SOLVER_CONCAT(ballista_solver_registered_, __LINE__) = \
      ::ballista::register_solver(__VA_ARGS__);                                                \
  }
