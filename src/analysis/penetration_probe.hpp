#pragma once
// Penetration measurements of a run with a `penetration:` section (thesis seed 000 ch. 5 and
// §7.2, Figs. 7.4-7.7): depth of the deepest penetrator particle and of the cavity tip against
// time since firing, rate of penetration by a smoothing local-polynomial derivative, steady-state
// linear fit, stop time, penetrator kinetic energy (total and per segment) and the final channel
// radius profile, with the hydrodynamic predictions of eq. 3.1-3.4 for comparison.
#include <cstdint>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "analysis/hole_profile.hpp"
#include "analysis/jet_remainder.hpp"
#include "core/state_archive.hpp"
#include "geometry/grid_axes.hpp"
#include "io/summary_writer.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class PenetrationProbe {
 public:
  /// Reads the penetration section, the penetrator's segments and the two densities.
  explicit PenetrationProbe(const Scenario& sc);

  /// History columns: penetration_time, penetration_depth, cavity_depth,
  /// penetrator_kinetic_energy, segment_kinetic_energy_<k> (k = 0 .. segments-1).
  std::vector<std::string> columns() const;
  /// The columns whose `nan` means "not yet applicable" (penetration_time before the main stage),
  /// not garbage.
  static std::vector<std::string> nan_when_not_applicable() { return {"penetration_time"}; }

  /// Values of those columns for the current points. `fired` is false during preparation stages
  /// (time and depths are then NaN and 0, nothing is recorded); otherwise the sample at
  /// `time_since_fire` (s) joins the series the summary is computed from.
  /// `scale` turns per-point sums into physical totals (2 pi in axisymmetric runs). `all_entered`:
  /// no point of the run waits for its activation (every segment of the penetrator is in).
  std::vector<double> sample(const FieldStore& points, bool fired, double time_since_fire, double scale,
                             bool all_entered = true);

  /// Writes penetration.csv (time, depth, cavity_depth, rate, cavity_rate) and channel.csv
  /// (depth, radius) into out_dir and fills `out` (the summary's "penetration" object).
  void finish(const FieldStore& points, const std::string& out_dir, double main_duration, JsonValue& out);

  /// Checkpoint: the recorded series (under "penetration."), its first `samples` entries (all by
  /// default: fewer for the state before the latest samples).
  void save_state(StateArchive& archive, std::size_t samples = SIZE_MAX) const;
  /// With penetration.end_when_spent: true from the first sample at which every segment of the
  /// penetrator has entered, its kinetic energy has fallen since, and it is at most that share of
  /// its peak so far.
  bool spent() const { return spent_sample_ >= 0; }
  std::size_t samples() const { return t_.size(); }
  void load_state(const StateArchive& archive);

  /// Depth below the target's struck face along the direction of flight, m (negative above it).
  double depth_of(const Vec3& x) const { return depth_of_coordinate(x[axis_]); }
  double depth_of_coordinate(double axial) const { return direction_ * (axial - surface_); }
  /// Distance from the line of flight, m (the radius x in axisymmetric runs).
  double lateral_of(const Vec3& x) const;

  /// Depth of the foremost penetrator point, m (negative while it is above the target's face;
  /// -inf with no penetrator point).
  double penetrator_front(const FieldStore& points) const;
  /// Depth of the cavity tip, m: the top of the shallowest target material that is not debris
  /// (debris: below) within axis_radius of the line of flight and below the face; the full target
  /// depth once nothing is left there (perforation). The channel profile also skips debris.
  double cavity_depth(const FieldStore& points) const;
  /// The same; `floor`: whether intact target material was found on the axis (false: the
  /// returned depth is the target's bottom).
  double cavity_depth(const FieldStore& points, bool& floor) const;

 private:
  /// Whether point p is debris: failed, of a material whose failure erodes its stress
  /// (`failure.erosion` other than none). A failed point that keeps its stress is solid.
  struct Debris {
    const double* failed;                ///< null: no point has a failure criterion
    const std::int64_t* material;
    const std::vector<char>* erodes;
    bool operator()(Index p) const;
  };
  Debris debris_of(const FieldStore& points) const;
  /// Points of `body` (not debris) for the wall measure, with their depth below `face`: where they
  /// are now, or (seeded_axial) where they were seeded through the layer.
  std::vector<LateralPoint> lateral_points(const FieldStore& points, int body, double face,
                                           bool seeded_axial = false) const;
  /// summary.json "path_cells": the cells along the line of flight over the depths [from, to] (the
  /// layers' faces to the tunnel's end) against the finest ones there, and the depth from which
  /// they are coarser (a graded grid whose band ends before the tunnel does).
  JsonValue path_cells(double from, double to) const;
  /// summary.json "beyond_tunnel": penetrator points beyond the tunnel's end (analysis/beyond_tunnel.hpp),
  /// null when the target has no floor on the axis. `points`: how many; `front_within`: the deepest
  /// penetrator point not beyond it (m, 0 if none).
  JsonValue beyond_tunnel_of(const FieldStore& points, int& points_beyond, double& front_within) const;
  /// summary.json "holes": the hole through each layer (entrance and smallest diameter).
  JsonValue layer_holes(const FieldStore& points) const;
  /// Records what is left of the jet when its front (penetrator_front) first passes the back face
  /// of each layer.
  void record_layer_exits(const FieldStore& points, double front, double time, double scale);
  /// summary.json holes.<layer>.jet_behind: that record beside the hydrodynamic erosion.
  JsonValue jet_behind(std::size_t layer) const;

  /// The jet when its front passed a layer's back face (sample: the series' length then).
  struct LayerExit {
    bool reached = false;
    std::size_t sample = 0;
    double time = 0.0;
    JetRemainder jet;
  };

  PenetrationSpec spec_;
  std::vector<int> layers_;  ///< body indices of spec_.layers
  std::vector<double> layer_face_, layer_thickness_;  ///< m: struck face (axial coordinate) and thickness
  std::vector<double> layer_density_;                 ///< kg/m^3
  std::vector<LayerExit> layer_exit_;
  std::vector<JetSegmentLine> jet_lines_;             ///< the penetrator's segments, tip first
  LateralGeometry lateral_geometry_ = LateralGeometry::ThreeD;
  double lateral_cell_ = 0.0, axial_cell_ = 0.0;  ///< m: the finest cells across and along the flight
  bool patched_ = false;  ///< the grid has patches (grid.patches): no level of a grid study
  GridAxes axes_;                                  ///< a graded grid's nodes (empty axes: uniform grid)
  int penetrator_ = -1, target_ = -1;  ///< body indices
  std::vector<char> erodes_;           ///< per material index: its failed points are eroded (debris)
  int axis_ = 1, nd_ = 3;
  double direction_ = -1.0, surface_ = 0.0;
  Vec3 line_point_;                    ///< a point on the line of flight
  int segments_ = 1;
  double rho_p_ = 0.0, rho_t_ = 0.0, length_ = 0.0, speed_ = 0.0, cell_ = 0.0;
  double radius_cells_ = 0.0;  ///< the thinnest segment radius over the cell size
  static constexpr double kResolvedRadiusCells = 4.0;  ///< cells across the radius for a resolved rate
  std::string fingerprint_;    ///< physics_fingerprint of the run's resolved deck
  std::string configuration_;  ///< configuration_fingerprint of it (physics and cells)
  std::vector<double> t_, depth_, cavity_;
  std::vector<double> kinetic_;      ///< J: the penetrator's kinetic energy per sample
  double peak_kinetic_ = 0.0;        ///< J: the largest of kinetic_
  std::int64_t entered_sample_ = -1;  ///< the first sample with every segment in, -1 before
  std::int64_t spent_sample_ = -1;    ///< end_when_spent: the sample it held first, -1 before
  /// end_when_spent: notes the newest sample if it is the first at which the penetrator is spent.
  void check_spent(bool all_entered);
};

}  // namespace ballista
