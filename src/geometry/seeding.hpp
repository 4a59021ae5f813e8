#pragma once
// Seeding material points of a body on a regular lattice aligned with the grid cells.
#include "core/field_store.hpp"
#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Declares the fields every solver's points carry, in the order of their keys in core/point_fields.hpp.
void declare_point_fields(FieldStore& points);

/// The point fields whose values are per radian of revolution in axisymmetric runs and per metre
/// of thickness in 2D runs (mass, volumes, energies: seed_body scales them so), for the unit
/// attributes of the particle files.
std::vector<std::string> extensive_point_fields();

/// The common fields of newly seeded points, written as every seeder writes them.
class SeededPoints {
 public:
  /// Appends n points to `points` (resized; ids continue from next_id as set() is called).
  SeededPoints(FieldStore& points, Index n);
  /// The q-th new point: the next id, body and material, x = x0 = at, velocity v, F = R = I, the
  /// reference and current volume `volume`, mass rho0 volume, the half size of its domain.
  void set(Index q, std::int64_t& next_id, int body_index, int material_index, double rho0, const Vec3& at,
           const Vec3& v, double volume, const Vec3& half_size);

 private:
  Index first_;
  std::int64_t *id_, *body_, *material_;
  Vec3 *x_, *x0_, *v_, *half_;
  Mat3 *F_, *R_;
  double *mass_, *vol0_, *vol_;
};

/// The spacing of the lattice `body` is seeded on: its own point_spacing if given (peridynamics),
/// else the grid cell size over particles_per_cell, m.
inline double seed_spacing(const BodySpec& body, double cell_size) {
  return body.point_spacing > 0.0 ? body.point_spacing : cell_size / body.particles_per_cell;
}

/// Appends the points of `body` to `points`: particles_per_cell^dim points per grid cell of size
/// h (or the lattice of the body's point_spacing), at sub-cell centres inside the shape; or, with
/// seeding `elements`, one per tetrahedron of its mesh (geometry/element_seeding.hpp).
/// Mass = rho0 * volume; in axisymmetric runs volumes and masses are per radian
/// (volume = r * area), in plane strain per metre of thickness.
/// Ids continue from next_id. Returns the number of points added (error if zero).
Index seed_body(const BodySpec& body, int body_index, int material_index, const Material& material,
                const GridSpec& grid, Dimension dim, FieldStore& points, std::int64_t& next_id);

/// Upper bound of the points seed_body would create for `body` (its segments for rods and jets):
/// the lattice points of its bounding box inside the grid box (its tetrahedra when seeded at
/// them). Cheap; used to estimate memory before anything is allocated.
double lattice_point_bound(const BodySpec& body, const GridSpec& grid, Dimension dim);

/// Marks the points of `body` lying within one point spacing of the named surface for pressure
/// load k: field "load_area_<k>" gets the reference area vector N dA0 (outward normal times the
/// point's share of the surface; per radian in axisymmetric runs). Returns the number marked.
Index mark_pressure_surface(const LoadSpec& load, int k, const BodySpec& body, int body_index,
                            double h, Dimension dim, FieldStore& points);

}  // namespace ballista
