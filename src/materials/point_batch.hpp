#pragma once
// A few material points updated through Material::update with a MaterialBatch, exactly as the
// solvers and the single-element driver call a model (MaterialAdapter: polar decomposition,
// unrotated frame, kernel, rotate back). Used by the A6 checks, which need several points with
// independently prescribed F and L and the optional algorithmic tangent, neither of which the
// single-element driver (driver/point_driver.hpp) exposes, and by the prestress of a confined
// body (points/prestress.hpp), which drives trial points from a committed state.
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/tensor.hpp"
#include "materials/material.hpp"

namespace ballista {

class PointBatch {
 public:
  /// n points at F = R = I, zero stress, state fields at their initial values.
  PointBatch(const Material& m, Index n);

  Index size() const { return n_; }
  Mat3& F(Index p) { return F_[p]; }            ///< F_new on step(); F_n after it
  Mat3& F_old(Index p) { return F_old_[p]; }    ///< F at the start of the step
  Mat3& L(Index p) { return L_[p]; }            ///< velocity gradient over the step
  Mat3& R(Index p) { return R_[p]; }
  Mat3& stress(Index p) { return stress_[p]; }  ///< spatial Cauchy stress
  Mat3 stress_bar(Index p) const { return unrotate(R_[p], stress_[p]); }
  const std::vector<std::string>& state_names() const { return state_names_; }
  double& state(int field, Index p) { return state_[static_cast<size_t>(field)][p]; }

  /// Sets F_new of point p and L = (F_new F_old^-1 - I)/dt (thesis seed 000 eq. 4.10), with
  /// F_old = the current F of the point.
  void set_F_eq410(Index p, const Mat3& F_new, double dt);

  /// One update of all points over dt; `tangent` (36 doubles per point) is passed as
  /// MaterialBatch::tangent when non-null.
  void step(double dt, double* tangent = nullptr);

  /// Copies stress, R, F, F_old and the state of point `from` of `src` (same model) to point `to`.
  void copy_point(const PointBatch& src, Index from, Index to);

 private:
  const Material& m_;
  Index n_;
  FieldStore store_;
  std::vector<Index> all_;
  Mat3 *F_, *F_old_, *L_, *R_, *stress_;
  std::vector<std::string> state_names_;
  std::vector<double*> state_;
};

}  // namespace ballista
