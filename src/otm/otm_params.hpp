#pragma once
// The deck's otm.* parameters: their spec list (names, units, defaults, ranges; docs/deck.md) and
// the typed values the solver reads once.
#include <vector>

#include "materials/material.hpp"

namespace ballista {

/// The spec of every otm.* key (the order `ballista info` lists them in).
std::vector<ParamSpec> otm_params();

/// The otm.* section as the solver uses it.
struct OtmParams {
  double gamma = 1.8;                ///< LME locality gamma = beta h^2
  double support_tolerance = 1e-4;   ///< weight cut-off of the support radius
  int min_support = 0;               ///< fewest support nodes of a point (0: dimension + 2)
  bool penalty_walls = false;        ///< wall_model: penalty (else constraint)
  double penalty = 1.0;              ///< penalty walls: spring factor on the node's stiffness bound
  bool line_search = true;           ///< backtracking line search in the LME Newton solve
  bool adaptivity = false;           ///< split points and re-generate nodes
  double split_stretch = 2.0;        ///< adaptivity: split beyond this times the seeded spacing
  bool interpolate_split_state = true;  ///< adaptivity: split_state interpolate (else copy)
  double node_gap = 1.0;             ///< adaptivity: re-generate when the nearest node is farther (x h)
  double node_crowding = 0.25;       ///< adaptivity: re-generate when two nodes come closer (x h)
  double max_condition = 1e6;        ///< adaptivity: re-generate beyond this LME Hessian condition number
  bool shared_nodes = false;         ///< nodes: shared (one node set over every body), else per_body
  bool fbar = false;                 ///< anti_locking: fbar (otm_fbar.hpp)
  bool contact = false;              ///< contact: pinball (otm_contact.hpp), else none
  double contact_penalty = 1.0;      ///< pinball contact: spring factor on the points' stiffness bound
  bool symmetric_step_bound = false;  ///< step_bound: symmetric (rows of M^-1/2 K M^-1/2), else gershgorin
};

/// Reads the section (Scenario::solver_params of an otm deck: every key present, the deck reader
/// filled the defaults).
OtmParams read_otm_params(const ParamValues& section);

}  // namespace ballista
