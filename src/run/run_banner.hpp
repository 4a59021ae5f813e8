#pragma once
// What a run is about to compute, logged before its first step: the solver, the particles of each
// body, the memory taken and an estimate of the steps, so that a deck much larger or longer than
// meant is seen at once rather than after an hour.
#include <cstdint>
#include <string>

#include "core/communicator.hpp"
#include "core/solver.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// The banner's text (several lines). `dt` is the stable step at the start (0 on a restart: no
/// estimate); `pending` the points inserted later (a jet). Collective over `comm` (the counts of
/// every rank); every rank returns the same text.
std::string run_banner(const Scenario& sc, Solver& solver, double dt, std::int64_t pending, const Communicator& comm);

/// The steps to the end of the run at a stable step `dt`: [least, most], the stages that end by a
/// criterion counted at their minimum and at their maximum duration.
struct StepEstimate {
  double least = 0.0, most = 0.0;
};
StepEstimate estimate_steps(const Scenario& sc, double dt);

}  // namespace ballista
