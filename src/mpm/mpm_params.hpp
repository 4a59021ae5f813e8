#pragma once
// The deck's mpm.* parameters: their spec list (names, units, defaults, ranges; docs/deck.md) and
// the typed values the solver reads once.
#include <vector>

#include "materials/material.hpp"
#include "mpm/anti_locking.hpp"
#include "mpm/bulk_viscosity.hpp"
#include "mpm/shape_functions.hpp"

namespace ballista {

/// The spec of every mpm.* key, in the order docs/deck.md lists them.
std::vector<ParamSpec> mpm_params();

/// The mpm.* section as the solver uses it.
struct MpmParams {
  enum class Update { Usl, Musl, Usavg };
  ShapeKind shape = ShapeKind::Linear;
  Update update = Update::Musl;
  double flip = 1.0;                 ///< FLIP fraction of the velocity update (1 FLIP, 0 PIC)
  int sort_every = 20;               ///< steps between particle sorts by cell (0 = never)
  AntiLocking anti_locking = AntiLocking::None;
  int fbar_patch = 1;                ///< F-bar patch edge, cells (1: each cell on its own)
  double rebalance_imbalance = 0.1;  ///< repartition when the largest rank holds > (1 + this) x the mean
  int xpic_order = 1;                ///< 1 = PIC for the PIC share
  BulkViscosity bulk_viscosity;      ///< C_L and C_Q (0: off)
  double distortion_limit = 1000.0;  ///< RMS isochoric stretch beyond which F is reset (0 = never)
  int multirate_max_ratio = 1;       ///< most substeps of the fast points per step (1: one step for all)

  /// XPIC needs its two extra node arrays (order > 1 with a PIC share).
  bool xpic_arrays() const { return xpic_order > 1 && flip < 1.0; }
  /// Extra node arrays as a count of Vec3 per node and field: XPIC's prev and target, USAVG's
  /// constrained first-half velocity.
  /// Multi-rate stepping's held share (mass, force, u, u0, path, v_n; its contact sums).
  int extra_node_arrays() const {
    return (xpic_arrays() ? 2 : 0) + (update == Update::Usavg ? 1 : 0) + (multirate_max_ratio > 1 ? 7 : 0);
  }
};

/// Reads the section (Scenario::solver_params of an mpm deck: every key present, the deck reader
/// filled the defaults).
MpmParams read_mpm_params(const ParamValues& section);

}  // namespace ballista
