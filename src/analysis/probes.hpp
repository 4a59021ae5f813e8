#pragma once
// Probes: scalar measures of the current state, written to history.csv and summary.json.
#include <string>
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"
#include "core/solver.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Checks that every probe can be evaluated on these points (fields exist and are scalars);
/// throws DeckError at the probe's line otherwise.
void validate_probes(const std::vector<ProbeSpec>& probes, const FieldStore& points);

/// Value of one probe. Body extents and radii use each particle's deformed domain
/// (x_p + F_p * corner of half_size), not only its centre, so they measure the body's surface.
///  extent:     max - min of the domain along `axis`, m
///  max_radius: largest distance from the symmetry axis (through `center`, along `axis`) of the
///              domains of particles whose centre is within `distance` of the plane, m
///  field_max:  maximum of a scalar field over the body
///  energy:     one of the energy totals, J
/// Returns NaN when no particle qualifies.
/// `body` is the probe's body index in deck order, -1 for all bodies.
double evaluate_probe(const ProbeSpec& probe, int body, const FieldStore& points,
                      const EnergyTotals& energy, Dimension dim, const Communicator& comm);

}  // namespace ballista
