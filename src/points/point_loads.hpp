#pragma once
// External loads on points, shared by every solver: the deck's loads, each of a registered kind
// (points/load_registry.hpp, kinds in points/loads/), summed into one force per point at the
// start of each step.
#include <memory>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "points/load_registry.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class PointLoads {
 public:
  using SurfaceForce = ::ballista::SurfaceForce;

  /// Forces of every load of `sc` on the points at `time`. Without loads nothing is allocated.
  void compute(const Scenario& sc, const FieldStore& points, double time);

  /// External force on each point this step, N (all loads; empty if the deck has no loads).
  const std::vector<Vec3>& total() const { return fext_; }
  /// The surface-traction part of total() (empty if no pressure load acts).
  const std::vector<Vec3>& traction() const { return ftrac_; }
  /// Each surface traction with its point of action.
  const std::vector<SurfaceForce>& surface_forces() const { return surface_forces_; }

  /// History columns of the loads (an indenter's <name>_fx, _fy, _fz), in deck order.
  static std::vector<std::string> history_columns(const Scenario& sc);
  /// Their values at the last compute() (zeros before the first).
  std::vector<double> history_values(const Scenario& sc) const;

 private:
  std::vector<std::unique_ptr<Load>> loads_;  ///< built from the deck at the first compute()
  std::vector<Vec3> fext_;
  std::vector<Vec3> ftrac_;
  std::vector<SurfaceForce> surface_forces_;
};

}  // namespace ballista
