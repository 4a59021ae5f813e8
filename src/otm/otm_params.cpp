// The deck's otm.* parameters: names, units, defaults and ranges (docs/deck.md; seed 003).
#include "otm/otm_params.hpp"

#include "points/solver_registry.hpp"

namespace ballista {

std::vector<ParamSpec> otm_params() {
  ParamSpec gamma{"gamma", "1",
                  "LME locality gamma = beta h^2 (h = grid.cell_size, the nodal spacing; seed 003 Fig. 5-5): larger "
                  "is more local (the finite-element limit), smaller smoother",
                  false, 1.8, 0.0, 50.0, true};
  ParamSpec tol{"support_tolerance", "1",
                "weight cut-off of the support radius h sqrt(-ln(tol)/gamma)", false, 1e-4, 0.0, 0.1, true};
  ParamSpec minsup{"min_support", "1", "fewest support nodes of a point (0: dimension + 2)", false, 0, 0, 1000};
  minsup.integer = true;
  const ParamSpec wall = word_param("wall_model",
                              "rigid walls (faces marked wall): constraint (no normal displacement into the wall) or "
                              "penalty (a spring on the crossing; seed 003 ch. 4)",
                              {"constraint", "penalty"});
  ParamSpec pen{"penalty", "1",
                "penalty walls: spring k_a = penalty m_a omega_a^2 (the node's own stiffness bound times this)", false,
                1.0, 0.0, 100.0, true};
  const ParamSpec ls = word_param("line_search", "backtracking line search in the LME Newton solve (seed 003 Fig. 5-5)",
                            {"on", "off"});
  const ParamSpec adapt = word_param("adaptivity",
                                     "split stretched points and re-generate the nodes on the lattice when they no "
                                     "longer resolve the points (seed 003 ch. 5; otm_adaptivity.hpp)",
                                     {"off", "on"});
  ParamSpec split{"split_stretch", "1", "adaptivity: split a point whose extent exceeds this times its seeded spacing",
                  false, 2.0, 1.0, 100.0, true};
  const ParamSpec split_state = word_param(
      "split_state",
      "adaptivity: the state of a split point's two children: interpolate (the parent's moved along the limited "
      "linear reconstruction of its neighbourhood, F by its polar factors; seed 003 ch. 5, split_state.hpp) or copy "
      "(both take the parent's)",
      {"interpolate", "copy"});
  ParamSpec gap{"node_gap", "1",
                "adaptivity: re-generate the nodes when a point's nearest node is farther than this times h", false,
                1.0, 0.0, 100.0, true};
  ParamSpec crowd{"node_crowding", "1",
                  "adaptivity: re-generate the nodes when two nodes of a body come closer than this times h", false,
                  0.25, 0.0, 1.0};
  ParamSpec cond{"max_condition", "1",
                 "adaptivity: re-generate the nodes when a point's LME Hessian condition number exceeds this", false,
                 1e6, 1.0, 1e300};
  const ParamSpec nodes = word_param("nodes",
                                     "node sets: per_body (each body its own nodes; bodies interact through contact: pinball) or shared "
                                     "(one node set over every body: bodies move together where they touch, no slip "
                                     "and no separation, as MPM's single_field)",
                                     {"per_body", "shared"});
  const ParamSpec locking = word_param("anti_locking",
                                       "volumetric locking treatment: none, or fbar (each point's volume change over "
                                       "the step replaced by its average over the supports of its nodes; otm_fbar.hpp)",
                                       {"none", "fbar"});
  const ParamSpec contact = word_param("contact",
                                       "contact between bodies with their own nodes: none (they pass through each "
                                       "other) or pinball (a frictionless penalty between the material points of "
                                       "different bodies; Belytschko & Neal 1991; otm_contact.hpp)",
                                       {"none", "pinball"});
  ParamSpec cpen{"contact_penalty", "1",
                 "pinball contact: spring k = contact_penalty / 2 min(m_p w_p^2, m_q w_q^2) (the points' stiffness "
                 "bounds times this)",
                 false, 1.0, 0.0, 100.0, true};
  const ParamSpec bound = word_param(
      "step_bound",
      "the stable step's bound on omega_max^2: gershgorin (the largest row sum of M^-1 K) or symmetric (of "
      "M^-1/2 K M^-1/2, the same eigenvalues: as large on a regular lattice, far larger steps where a node "
      "carries little mass; otm_solver.cpp, stable_dt)",
      {"gershgorin", "symmetric"});
  return {gamma, tol, minsup, wall, pen, ls, adapt, split, split_state, gap, crowd, cond, nodes, locking, contact, cpen,
          bound};
}

OtmParams read_otm_params(const ParamValues& P) {
  OtmParams o;
  o.gamma = P.at("gamma");
  o.support_tolerance = P.at("support_tolerance");
  o.min_support = static_cast<int>(P.at("min_support"));
  o.penalty_walls = P.choices.at("wall_model") == "penalty";
  o.penalty = P.at("penalty");
  o.line_search = P.choices.at("line_search") == "on";
  o.adaptivity = P.choices.at("adaptivity") == "on";
  o.split_stretch = P.at("split_stretch");
  o.interpolate_split_state = P.choices.at("split_state") == "interpolate";
  o.node_gap = P.at("node_gap");
  o.node_crowding = P.at("node_crowding");
  o.max_condition = P.at("max_condition");
  o.shared_nodes = P.choices.at("nodes") == "shared";
  o.symmetric_step_bound = P.choices.at("step_bound") == "symmetric";
  o.fbar = P.choices.at("anti_locking") == "fbar";
  o.contact = P.choices.at("contact") == "pinball";
  o.contact_penalty = P.at("contact_penalty");
  return o;
}

}  // namespace ballista
