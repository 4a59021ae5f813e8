#include "run/simulation.hpp"

#include "core/error.hpp"
#include "points/solver_registry.hpp"
#include "run/run_loop.hpp"

namespace ballista {

std::vector<std::unique_ptr<Material>> make_materials(const Scenario& sc) {
  std::vector<std::unique_ptr<Material>> out;
  for (const auto& m : sc.materials) {
    const MaterialFactory* f = find_material(m.model);
    if (!f)
      throw DeckError(m.mark.file, m.mark.line, m.mark.column, m.mark.key_path + ".model",
                      "unknown material model '" + m.model + "'");
    out.push_back(f->create(m.name, m.params));
  }
  return out;
}

void check_distributed(const Scenario& sc, const SolverFactory& f, const Communicator& comm) {
  if (comm.distributed() && !f.distributed)
    throw DeckError(sc.file, 0, 0, "simulation.solver",
                    "solver '" + sc.simulation.solver + "' runs on one MPI rank only so far (" +
                        std::to_string(comm.size()) + " ranks were started); run it without mpirun, or with -np 1");
}

std::unique_ptr<Solver> make_solver(const Scenario& sc, const Communicator& comm) {
  const SolverFactory* f = find_solver(sc.simulation.solver);
  if (!f) {
    std::string names;
    for (const auto& s : solver_registry()) names += (names.empty() ? "" : ", ") + s.name;
    throw Error("unknown solver '" + sc.simulation.solver + "' (registered: " + names + ")");
  }
  check_distributed(sc, *f, comm);
  return f->create(sc, make_materials(sc), comm);
}

RunResult run_simulation(const Scenario& sc, const RunOptions& opt) { return RunLoop(sc, opt).run(); }

}  // namespace ballista
