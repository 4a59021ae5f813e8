#pragma once
// Multi-velocity-field contact on the MPM grid (Bardenhagen, Brackbill & Sulsky, CMAME 187 (2000)
// 529; Bardenhagen, Guilkey, Roessig, Brackbill, Witzel & Foster, CMES 2 (2001) 509; Uintah's
// friction contact, thesis seed 000 ch. 2). Applied twice per step, after the momenta are mapped
// to the grid and after they are updated (Nairn, Hammerquist & Smith, CMAME 362 (2020) 112859).
// Every field (a body, or bodies joined into one) has its own nodal mass and momentum. At a node
// where two fields have mass, each field's velocity is compared with the centre-of-mass
// velocity; a field approaching the other along the contact normal loses its normal relative
// velocity (no interpenetration) and its tangential relative velocity is cut by Coulomb friction mu
// times the normal correction, or stopped (stick). Fields that separate are left alone. Where three
// or more fields meet, the same law acts pair by pair with equal and opposite impulses, so that the
// node's momentum is kept (grid_contact.cpp, resolve_pairs).
#include <cstdint>

#include "core/parallel.hpp"
#include "core/tensor.hpp"
#include "mpm/grid_geometry.hpp"

namespace ballista {

/// Work of the contact impulses of one pass (J, per-point-sum units), and the part of it done by
/// the tangential (friction) impulses.
struct ContactWork {
  double total = 0.0;
  double friction = 0.0;
};

/// The grid arrays of `fields` velocity fields, each `nodes` long, stored field after field.
struct FieldGrid {
  int fields = 1;
  Index nodes = 0;
  const double* mass = nullptr;  ///< kg per field and node
  /// sum_p w_p grad N_I(x_p) per field and node: it points out of the field's material. w_p is the
  /// point's mass (kg/m in a planar or 3D run: minus the gradient of the mass density; in an
  /// axisymmetric run the mass per radian, so minus the gradient of rho r, which is -m_I / r_I
  /// along r even inside a uniform body), or with contact.axisymmetric_normal: density the mass
  /// per radian over the point's radius (kg/m^2: minus the gradient of rho, zero inside).
  const Vec3* grad = nullptr;
  const double* friction = nullptr;  ///< fields x fields Coulomb coefficients
  /// Several ranks: per node, 0 where a lower rank books the work of this shared node (the node's
  /// velocities are corrected on every rank that holds it). nullptr: every node counts.
  const std::uint8_t* counted = nullptr;
  /// The gap check (optional): sum_p N_I V_p per field and node, and the fraction of the node's
  /// volume (GridGeometry::node_volume) the fields must fill together to be in contact there.
  const double* volume = nullptr;
  double min_volume_fraction = 0.0;
  const GridGeometry* geom = nullptr;
  bool axisymmetric = false;
};

/// Applies contact to the nodal velocities `vel` (fields x nodes) in place and returns the work of
/// the contact impulses m c of this pass alone, with the midpoint velocity (v_before + v_after) / 2:
/// the kinetic-energy change the correction makes. The MPM solver books the step's impulses with
/// one midpoint from `impulse` instead (MpmSolver::book_impulses). Nodes lighter than tiny_mass
/// carry no material. The contact normal of field k at a node is the unit vector of (field k's
/// outward vector - the sum of the other fields'), i.e. out of k towards the others (an "average"
/// of the two bodies' mass-gradient normals, as in Nairn's multimaterial MPM, which makes the two
/// normals of a pair exactly opposite so that the pair's momentum is conserved).
/// With `impulse` (fields x nodes) each correction c is also added to impulse[k], and its
/// tangential (friction) part to friction_impulse[k], so that the caller can book the step's
/// contact impulses with one midpoint (MpmSolver::book_impulses).
ContactWork apply_grid_contact(const FieldGrid& g, Vec3* vel, double tiny_mass, Vec3* impulse = nullptr,
                               Vec3* friction_impulse = nullptr);

}  // namespace ballista
