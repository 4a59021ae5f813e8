#pragma once
// External loads on points, shared by every solver: body forces (gravity), surface pressure with
// load curves (Nanson-mapped onto the current surface), rigid indenters (LAMMPS fix indent) and the
// manufactured body forces of CATALOGUE B1 and B2. Recomputed at the start of each step.
#include <cstdint>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class PointLoads {
 public:
  /// A surface traction and the point where it acts (the point's face on the loaded surface).
  struct SurfaceForce {
    Vec3 point;  ///< m
    Vec3 force;  ///< N
    Index index = 0;  ///< the point it acts on
  };

  /// Forces of every load of `sc` on the points at `time`. Without loads nothing is allocated.
  void compute(const Scenario& sc, const FieldStore& points, double time);

  /// External force on each point this step, N (all loads; empty if the deck has no loads).
  const std::vector<Vec3>& total() const { return fext_; }
  /// The surface-traction part of total() (empty if no pressure load acts).
  const std::vector<Vec3>& traction() const { return ftrac_; }
  /// Each surface traction with its point of action.
  const std::vector<SurfaceForce>& surface_forces() const { return surface_forces_; }

  /// History columns of the loads: <name>_fx, _fy, _fz of each indenter (empty without one).
  static std::vector<std::string> history_columns(const Scenario& sc);
  /// Their values at the last compute(): the force of the points on each indenter, N (the
  /// reaction), summed over this rank's points in a fixed order (zeros before the first compute).
  std::vector<double> history_values(const Scenario& sc) const;

 private:
  std::vector<Vec3> fext_;
  std::vector<Vec3> ftrac_;
  std::vector<SurfaceForce> surface_forces_;
  std::vector<Vec3> reactions_;  ///< per indenter, N
  /// Per load: the points with a loaded surface area (pressure loads), in index order, found
  /// once per layout of the points (FieldStore::layout_version) instead of a scan every step.
  std::vector<std::vector<Index>> surface_points_;
  std::uint64_t surface_layout_ = UINT64_MAX;
  /// Rebuilds surface_points_ if the points moved or changed in number since it was built.
  void update_surface_points(const Scenario& sc, const FieldStore& points);
};

}  // namespace ballista
