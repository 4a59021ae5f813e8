#include "analysis/penetration_probe.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <numbers>

#include <spdlog/spdlog.h>

#include "analysis/axis_distance.hpp"
#include "analysis/beyond_tunnel.hpp"
#include "analysis/convergence_statement.hpp"
#include "analysis/penetration_series.hpp"
#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "deck/physics_fingerprint.hpp"
#include "geometry/grid_axes.hpp"
#include "geometry/shape.hpp"
#include "io/history_writer.hpp"
#include "materials/failure.hpp"
#include "penetration/hydrodynamic.hpp"

namespace ballista {

namespace {

constexpr double kNotMeasured = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Half-extent along direction `a` of a point's current domain (F times the box of half-sizes h).
double half_extent(const Mat3& F, const Vec3& h, int a, int nd) {
  double e = 0.0;
  for (int j = 0; j < nd; ++j) e += std::abs(F(a, j)) * h[j];
  return e;
}

double density_of(const Scenario& sc, const std::string& material) {
  for (const auto& m : sc.materials)
    if (m.name == material) return m.params.number_or("density", 0.0);
  return 0.0;
}

}  // namespace

PenetrationProbe::PenetrationProbe(const Scenario& sc) : spec_(sc.penetration) {
  if (!spec_.enabled) throw Error("PenetrationProbe needs a penetration section");
  penetrator_ = body_index(sc, spec_.penetrator);
  target_ = body_index(sc, spec_.target);
  const BodySpec& pb = sc.bodies.at(penetrator_);
  const PenetratorSpec& ps = spec_.flight;
  axis_ = ps.axis;
  direction_ = ps.direction;
  surface_ = spec_.surface;
  fingerprint_ = physics_fingerprint(sc.resolved_yaml);
  configuration_ = configuration_fingerprint(sc.resolved_yaml);
  line_point_ = ps.nose;
  nd_ = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  segments_ = std::max<int>(1, static_cast<int>(pb.segments.size()));
  rho_p_ = density_of(sc, pb.material);
  rho_t_ = density_of(sc, sc.bodies.at(target_).material);
  // A formed jet's speed and length are not known before the run (reported as null).
  length_ = spec_.formed_jet ? kNotMeasured : ps.length;
  speed_ = spec_.formed_jet ? kNotMeasured : ps.speed;
  cell_ = sc.grid.cell_size;
  // A graded grid's finest cells across and along the line of flight, where the jet is.
  lateral_cell_ = axial_cell_ = cell_;
  if (sc.grid.graded()) {
    axes_ = build_grid_axes(sc.grid, nd_);
    lateral_cell_ = axial_cell_ = kInfinity;
    // The cells of the grid's bands: a patch refines a box, not the whole path, and the jet is as
    // resolved as the coarsest cells it crosses.
    GridAxes bands;
    bands.node = axes_.base;
    for (int a = 0; a < nd_; ++a) {
      double& finest = a == axis_ ? axial_cell_ : lateral_cell_;
      finest = std::min(finest, bands.smallest(a));
    }
    patched_ = !sc.grid.patches.empty();
    cell_ = lateral_cell_;
  }
  lateral_geometry_ = sc.simulation.dimension == Dimension::Axisymmetric ? LateralGeometry::Axisymmetric
                      : nd_ == 3                                         ? LateralGeometry::ThreeD
                                                                         : LateralGeometry::PlaneStrain;
  for (const std::string& name : spec_.layers) {
    const int b = body_index(sc, name);
    Vec3 lo, hi;
    shape_bounds(sc.bodies.at(b).shape, nd_, lo, hi);
    layers_.push_back(b);
    layer_face_.push_back(direction_ < 0 ? hi[axis_] : lo[axis_]);
    layer_thickness_.push_back(hi[axis_] - lo[axis_]);
    layer_density_.push_back(density_of(sc, sc.bodies.at(b).material));
  }
  layer_exit_.assign(layers_.size(), LayerExit{});
  // A failed point is debris only where its material's failure erodes its stress (docs/materials.md,
  // "Erosion"): with `failure.erosion: none` it keeps the full stress of its model and is as solid
  // as its neighbours (the casing's steel as the demo runs it: its failed points are the lip of the
  // hole, and counted as a hole they widened it by 1-1.7 mm, an amount that jumped between levels).
  for (const MaterialSpec& m : sc.materials) erodes_.push_back(m.params.choice("failure.erosion", "none") != "none");
  // Each segment's speed along the flight and mass per unit length of the modelled section: the
  // full disk in axisymmetry (the reporting scale makes per-radian masses full ones), a disk (3D)
  // or a strip 2r wide (plane strain) halved by each symmetry face through the line of flight.
  double section_fraction = 1.0;
  if (lateral_geometry_ != LateralGeometry::Axisymmetric)
    for (int a = 0; a < nd_; ++a)
      if (a != axis_ && (std::abs(sc.grid.lower[a] - line_point_[a]) < 1e-9 * std::max(1.0, std::abs(line_point_[a])) ||
                         std::abs(sc.grid.upper[a] - line_point_[a]) < 1e-9 * std::max(1.0, std::abs(line_point_[a]))))
        section_fraction *= 0.5;
  const auto line_of = [&](double radius, double length, const Vec3& velocity) {
    const double section =
        lateral_geometry_ == LateralGeometry::PlaneStrain ? 2.0 * radius : std::numbers::pi * radius * radius;
    return JetSegmentLine{direction_ * velocity[axis_], rho_p_ * section * section_fraction, length};
  };
  if (spec_.formed_jet) {  // no segments to follow behind the layers, no radius known in advance
    radius_cells_ = kNotMeasured;
    return;
  }
  if (pb.segments.empty()) {  // a rod: one piece at the penetrator's speed
    Vec3 v{};
    v[axis_] = direction_ * ps.speed;
    jet_lines_.push_back(line_of(0.5 * ps.diameter, ps.length, v));
  }
  for (const SegmentSpec& seg : pb.segments)
    jet_lines_.push_back(line_of(seg.shape.radius, seg.shape.length, seg.velocity));
  // Resolution of the penetrator: the thinnest segment's radius in cells. The hydrodynamic
  // verification (tests/verification/test_mpm_contact.cpp) reaches U_h within 1 % at 4 cells
  // across the radius and falls 7 % short at 2; a thinner penetrator is under-resolved.
  double radius = 0.5 * ps.diameter;
  for (const SegmentSpec& seg : pb.segments) radius = std::min(radius, seg.shape.radius);
  radius_cells_ = radius / cell_;
  if (radius_cells_ < kResolvedRadiusCells)
    spdlog::warn("penetrator '{}' is {:.3g} cells across its radius ({:.3g} m at cell_size {:.3g} m): the rate is "
                 "under-resolved (U_h is met within 1 % from {:g} cells; docs/validation.md, multi-field contact)",
                 spec_.penetrator, radius_cells_, radius, cell_, kResolvedRadiusCells);
}

double PenetrationProbe::lateral_of(const Vec3& x) const { return distance_from_axis(x, line_point_, axis_, nd_); }

PenetrationProbe::Debris PenetrationProbe::debris_of(const FieldStore& pts) const {
  return {pts.has(kFailed) ? pts.real(kFailed) : nullptr, pts.ints(kMaterialIndex), &erodes_};
}

bool PenetrationProbe::Debris::operator()(Index p) const {
  if (!failed || failed[p] <= 0.0) return false;
  const auto m = static_cast<std::size_t>(material[p]);
  return m < erodes->size() && (*erodes)[m];
}

std::vector<std::string> PenetrationProbe::columns() const {
  std::vector<std::string> c = {"penetration_time", "penetration_depth", "cavity_depth", "penetrator_kinetic_energy"};
  for (int k = 0; k < segments_; ++k) c.push_back("segment_kinetic_energy_" + std::to_string(k));
  return c;
}

double PenetrationProbe::penetrator_front(const FieldStore& pts) const {
  const auto* bid = pts.ints(kBodyIndex);
  const auto* x = pts.view(kPosition);
  double front = -kInfinity;
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == penetrator_) front = std::max(front, depth_of(x[p]));
  return front;
}

double PenetrationProbe::cavity_depth(const FieldStore& pts) const {
  bool floor = false;
  return cavity_depth(pts, floor);
}

double PenetrationProbe::cavity_depth(const FieldStore& pts, bool& floor) const {
  const auto* bid = pts.ints(kBodyIndex);
  const auto* x = pts.view(kPosition);
  const auto* F = pts.view(kDeformationGradient);
  const auto* half = pts.view(kHalfSize);
  const Debris debris = debris_of(pts);
  double tip = std::numeric_limits<double>::infinity(), bottom = 0.0;
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != target_) continue;
    // Eroded (failed) material is debris in the channel, not its floor or wall.
    if (debris(p)) continue;
    // Extent of the deformed domain along the axis: |F_a,j| h_j summed (the domain is F times a box).
    const double reach = half_extent(F[p], half[p], axis_, nd_);
    const double d = depth_of(x[p]);
    bottom = std::max(bottom, d + reach);
    // Material ejected above the face (d < 0) is not the cavity's floor.
    if (d >= 0.0 && lateral_of(x[p]) < spec_.axis_radius) tip = std::min(tip, std::max(0.0, d - reach));
  }
  floor = std::isfinite(tip);
  return floor ? tip : bottom;
}

std::vector<double> PenetrationProbe::sample(const FieldStore& pts, bool fired, double t, double scale,
                                             bool all_entered) {
  std::vector<double> seg(static_cast<size_t>(segments_), 0.0);
  const auto* bid = pts.ints(kBodyIndex);
  const auto* sid = pts.ints(kSegment);
  const auto* v = pts.view(kVelocity);
  const auto* m = pts.real(kMass);
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == penetrator_) {
      const auto k = static_cast<size_t>(std::clamp<std::int64_t>(sid[p], 0, segments_ - 1));
      seg[k] += 0.5 * m[p] * dot(v[p], v[p]) * scale;
    }
  double total = 0.0;
  for (double e : seg) total += e;
  double depth = 0.0, cavity = 0.0;
  if (fired) {
    const double front = penetrator_front(pts);
    depth = std::max(0.0, front);
    cavity = cavity_depth(pts);
    if (t_.empty() || t > t_.back()) {
      t_.push_back(t);
      depth_.push_back(depth);
      cavity_.push_back(cavity);
      kinetic_.push_back(total);
      peak_kinetic_ = std::max(peak_kinetic_, total);
      check_spent(all_entered);
      record_layer_exits(pts, front, t, scale);
    }
  }
  std::vector<double> row = {fired ? t : kNotMeasured, depth, cavity, total};
  row.insert(row.end(), seg.begin(), seg.end());
  return row;
}

void PenetrationProbe::check_spent(bool all_entered) {
  const auto newest = static_cast<std::int64_t>(kinetic_.size()) - 1;
  if (entered_sample_ < 0 && all_entered) entered_sample_ = newest;
  if (!(spec_.end_when_spent > 0.0) || spent_sample_ >= 0 || entered_sample_ < 0) return;
  // Fallen since the last segment came in, so that a slow last segment, whose own energy may be
  // below the share of the early peak, is not taken for a spent jet the moment it enters. A formed
  // jet is all in at t = 0, at rest: its energy must have fallen from its peak instead.
  const double at_entry = spec_.formed_jet ? peak_kinetic_ : kinetic_[static_cast<std::size_t>(entered_sample_)];
  const double now = kinetic_.back();
  if (peak_kinetic_ > 0.0 && now < at_entry && now <= spec_.end_when_spent * peak_kinetic_) spent_sample_ = newest;
}

void PenetrationProbe::finish(const FieldStore& pts, const std::string& out_dir, double main_duration, JsonValue& out) {
  namespace fs = std::filesystem;
  out = JsonValue::object();
  out["penetrator"] = spec_.penetrator;
  out["target"] = spec_.target;
  // A formed jet's speed, length and radius are the run's to find, not the deck's: null.
  const auto known = [](double v) { return std::isfinite(v) ? JsonValue(v) : JsonValue(); };
  if (spec_.formed_jet) out["formed_jet"] = true;
  out["impact_velocity"] = known(speed_);
  out["penetrator_density"] = rho_p_;
  out["target_density"] = rho_t_;
  out["penetrator_length"] = known(length_);
  out["segments"] = segments_;
  out["surface"] = surface_;

  // Rates by a smoothing local quadratic (thesis §7.2 differentiates with a local Lagrange
  // polynomial; a least-squares one over 2w+1 samples also damps the sampling noise).
  const int w = spec_.rate_half_window;
  std::vector<double> rate(t_.size(), kNotMeasured), cavity_rate(t_.size(), kNotMeasured);
  if (static_cast<int>(t_.size()) >= 2 * w + 1) {
    rate = local_polynomial_derivative(t_, depth_, w, 2);
    cavity_rate = local_polynomial_derivative(t_, cavity_, w, 2);
  }
  {
    HistoryWriter csv((fs::path(out_dir) / "penetration.csv").string(),
                      {"time", "depth", "cavity_depth", "rate", "cavity_rate"});
    for (size_t i = 0; i < t_.size(); ++i) csv.row({t_[i], depth_[i], cavity_[i], rate[i], cavity_rate[i]});
  }
  const double final_depth = depth_.empty() ? 0.0 : depth_.back();
  out["final_depth"] = final_depth;
  out["final_cavity_depth"] = cavity_.empty() ? 0.0 : cavity_.back();
  double max_depth = 0.0;
  for (double d : depth_) max_depth = std::max(max_depth, d);
  out["max_depth"] = max_depth;
  int strays = 0;
  double front_within = 0.0;  // the deepest penetrator point not beyond the tunnel's end
  out["beyond_tunnel"] = beyond_tunnel_of(pts, strays, front_within);
  // Arrival: the first sample with penetrator material below the target's face.
  JsonValue arrival;
  for (size_t i = 0; i < t_.size(); ++i)
    if (depth_[i] > 0.0) {
      arrival = i > 0 ? t_[i - 1] : t_[i];
      break;
    }
  out["arrival_time"] = arrival;
  // Stopped: the depth changes by less than stop_tolerance over at least the last tenth of the run;
  // a run that ended because the penetrator was spent has stopped by then, whatever is left of it.
  const double hold = spent() ? 0.0 : 0.1 * main_duration;
  const double stop = t_.size() >= 2 ? penetration_stop_time(t_, depth_, spec_.stop_tolerance, hold) : kNotMeasured;
  out["stop_time"] = std::isfinite(stop) ? JsonValue(stop) : JsonValue();
  if (spec_.end_when_spent > 0.0) {
    JsonValue& e = out["end_when_spent"];
    e = JsonValue::object();
    e["share"] = spec_.end_when_spent;
    e["time"] = spent() ? JsonValue(t_[static_cast<std::size_t>(spent_sample_)]) : JsonValue();
  }
  const SteadyFit fit = t_.size() >= 5 ? steady_state_fit(t_, depth_, rate) : SteadyFit{};
  out["steady_rate"] = fit.ok ? JsonValue(fit.slope) : JsonValue();
  JsonValue& sf = out["steady_fit"];
  sf = JsonValue::object();
  if (fit.ok) {
    sf["intercept"] = fit.intercept;
    sf["t_begin"] = fit.t_begin;
    sf["t_end"] = fit.t_end;
    sf["r2"] = fit.r2;
    sf["points"] = fit.points;
  }
  // Hydrodynamic theory (thesis eq. 3.1-3.4): U_h and the Birkhoff depth L sqrt(rho_p/rho_t);
  // a segmented penetrator also gets the fully particulated bound (lambda = 2, eq. 3.4).
  const bool have = rho_p_ > 0 && rho_t_ > 0 && !spec_.formed_jet;
  const double uh = have ? penetration::hydrodynamic_penetration_velocity(speed_, rho_p_, rho_t_) : kNotMeasured;
  out["hydrodynamic_rate"] = known(uh);
  out["rate_over_hydrodynamic"] = fit.ok && uh > 0 ? JsonValue(fit.slope / uh) : JsonValue();
  out["cells_across_radius"] = known(radius_cells_);
  // The radius's cells are the finest; a tunnel that runs on beyond the refined band ends in coarser
  // ones, and its depth is not the band's answer.
  // Points far beyond the tunnel's end (beyond_tunnel) open no tunnel: the channel ends where the
  // rest of the penetrator does.
  const double channel_depth =
      std::max(out.at("final_cavity_depth").as_number(), strays > 0 ? front_within : max_depth);
  double entry = 0.0;
  for (double face : layer_face_) entry = std::min(entry, depth_of_coordinate(face));
  const JsonValue cells = path_cells(entry, channel_depth);
  const bool along = cells.at("coarser_from_depth").kind() == JsonValue::Kind::Null;
  if (!along)
    spdlog::warn("the tunnel reaches {:.4g} m deep, but the finest cells along the line of flight ({:.3g} m) end "
                 "at {:.4g} m deep (cells up to {:.3g} m beyond): its end is not at the resolution "
                 "cells_across_radius states; extend grid.refine along the flight",
                 channel_depth, axial_cell_, cells.at("coarser_from_depth").as_number(), cells.at("coarsest").as_number());
  out["path_cells"] = cells;
  out["resolved"] = radius_cells_ >= kResolvedRadiusCells && along;
  const double ph = have ? penetration::birkhoff_depth(length_, rho_p_, rho_t_) : kNotMeasured;
  out["hydrodynamic_depth"] = known(ph);
  JsonValue& an = out["analytic"];
  an = JsonValue::array();
  if (have) {
    JsonValue b = JsonValue::object();
    b["name"] = "hydrodynamic (Birkhoff, eq. 3.2)";
    b["depth"] = ph;
    an.push_back(b);
    if (segments_ > 1) {
      JsonValue q = JsonValue::object();
      q["name"] = "particulated, lambda = 2 (eq. 3.4)";
      q["depth"] = penetration::particulated_jet_depth(length_, 2.0, rho_p_, rho_t_);
      an.push_back(q);
    }
  }

  // Final channel: the tunnel's wall radius in each depth bin (analysis/hole_profile.hpp: where
  // the target material is dense, so that debris lying in the tunnel is not wall), beside the
  // innermost target material's distance from the line of flight (inner edge of the particle
  // domains) down to the cavity tip.
  const auto* bid = pts.ints(kBodyIndex);
  const auto* x = pts.view(kPosition);
  const auto* F = pts.view(kDeformationGradient);
  const auto* half = pts.view(kHalfSize);
  std::vector<double> dd, rr;
  const int lat = axis_ == 1 ? 0 : 1;  // a lateral direction (exact in 2D; 3D uses the radial extent below)
  const Debris debris = debris_of(pts);
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != target_ || debris(p)) continue;
    const double reach = half_extent(F[p], half[p], lat, nd_);
    dd.push_back(depth_of(x[p]));
    rr.push_back(std::max(0.0, lateral_of(x[p]) - reach));
  }
  const int bins = spec_.channel_bins > 0 ? spec_.channel_bins
                                          : std::max(1, static_cast<int>(std::ceil(channel_depth / axial_cell_)));
  double max_radius = 0.0, wall_sum = 0.0;
  int wall_count = 0;
  JsonValue tunnel = JsonValue::object();
  {
    HistoryWriter csv((fs::path(out_dir) / "channel.csv").string(), {"depth", "radius", "innermost_radius"});
    if (channel_depth > 0 && !dd.empty()) {
      const ChannelProfile prof = channel_profile(dd, rr, channel_depth, bins);
      const std::vector<double> wall =
          wall_radii(lateral_points(pts, target_, surface_), 0.0, channel_depth, bins, lateral_geometry_,
                     {lateral_cell_});
      for (size_t i = 0; i < prof.depth.size(); ++i) {
        csv.row({prof.depth[i], wall[i], prof.radius[i]});
        if (std::isfinite(wall[i])) {
          max_radius = std::max(max_radius, wall[i]);
          wall_sum += wall[i];
          ++wall_count;
        }
      }
      // The rock's face around the line of flight may be crushed or blown off, leaving no wall in
      // the first bins: the entrance is where the wall begins, at the depth reported beside it.
      const auto first = std::find_if(wall.begin(), wall.end(), [](double w) { return std::isfinite(w); });
      const bool found = first != wall.end();
      tunnel["entrance_diameter"] = found ? JsonValue(2.0 * *first) : JsonValue();
      tunnel["entrance_depth"] =
          found ? JsonValue(channel_depth * static_cast<double>(first - wall.begin()) / bins) : JsonValue();
    }
  }
  out["max_channel_radius"] = max_radius;
  tunnel["mean_diameter"] = wall_count > 0 ? JsonValue(2.0 * wall_sum / wall_count) : JsonValue();
  tunnel["depth"] = channel_depth;
  out["tunnel"] = tunnel;
  out["holes"] = layer_holes(pts);
  out["physics_fingerprint"] = fingerprint_;
  out["configuration_fingerprint"] = configuration_;
  if (!spec_.convergence.path.empty())
    out["convergence"] = convergence_statement(spec_.convergence, fingerprint_, configuration_, axial_cell_, out,
                                              patched_);
}

JsonValue PenetrationProbe::beyond_tunnel_of(const FieldStore& pts, int& points_beyond, double& front_within) const {
  points_beyond = 0;
  bool floor = false;
  const double tunnel_end = cavity_depth(pts, floor);
  if (!floor) return JsonValue();  // perforated, or nothing on the axis: no tunnel's end to be beyond
  const auto* bid = pts.ints(kBodyIndex);
  const auto* x = pts.view(kPosition);
  const auto* m = pts.real(kMass);
  std::vector<double> depth, mass;
  for (Index p = 0; p < pts.size(); ++p)
    if (bid[p] == penetrator_) {
      depth.push_back(depth_of(x[p]));
      mass.push_back(m[p]);
    }
  const double margin = kBeyondTunnelCells * axial_cell_;
  const BeyondTunnel b = beyond_tunnel(depth, mass, tunnel_end, margin);
  points_beyond = b.points;
  front_within = std::max(0.0, b.deepest_within);
  if (b.points > 0)
    spdlog::warn("points of '{}' beyond the tunnel's end ({:.4g} m deep) by more than {:g} cells, in rock nothing "
                 "has opened: {} ({:.2g} % of its mass), the deepest at {:.4g} m. The deepest penetrator point (the "
                 "summary's depth) is not the depth of penetration; the tunnel's end (its cavity depth) is "
                 "(docs/penetration.md)",
                 spec_.penetrator, tunnel_end, kBeyondTunnelCells, b.points, 100.0 * b.mass_share, b.deepest);
  JsonValue out = JsonValue::object();
  out["tunnel_end"] = tunnel_end;
  out["margin"] = margin;
  out["points"] = b.points;
  out["mass_share"] = b.mass_share;
  out["deepest"] = b.points > 0 ? JsonValue(b.deepest) : JsonValue();
  return out;
}

std::vector<LateralPoint> PenetrationProbe::lateral_points(const FieldStore& pts, int body, double face,
                                                          bool seeded_axial) const {
  const auto* bid = pts.ints(kBodyIndex);
  const auto* x = pts.view(kPosition);
  const auto* x0 = seeded_axial && pts.has(kReferencePosition) ? pts.view(kReferencePosition) : x;
  const auto* F = pts.view(kDeformationGradient);
  const auto* half = pts.view(kHalfSize);
  const auto* vol = pts.real(kVolume);
  const int lat = axis_ == 1 ? 0 : 1;
  std::vector<LateralPoint> out;
  const Debris debris = debris_of(pts);
  for (Index p = 0; p < pts.size(); ++p) {
    if (bid[p] != body || debris(p)) continue;
    // The point's lateral half-extent in the current configuration (its domain is F times a box).
    const double reach = half_extent(F[p], half[p], lat, nd_);
    double volume = vol[p];
    if (seeded_axial) {
      // Binned where it was seeded through the layer, the point fills its slice of the seeded
      // thickness: its current volume over its current axial extent, times its seeded one (a plate
      // dished, or thinned at the lip of its hole, still fills its slice where it is solid).
      const double along = half_extent(F[p], half[p], axis_, nd_);
      if (along > 0.0) volume *= half[p][axis_] / along;
    }
    out.push_back({direction_ * (x0[p][axis_] - face), lateral_of(x[p]), volume, reach});
  }
  return out;
}

JsonValue PenetrationProbe::path_cells(double from, double to) const {
  JsonValue c = JsonValue::object();
  c["finest"] = axial_cell_;
  double coarsest = axial_cell_, coarser_from = kInfinity;
  const std::vector<double>& n = axes_.node[axis_];
  for (std::size_t k = 0; k + 1 < n.size(); ++k) {
    // The cell's depths along the flight, shallow end first; cells the path does not cross skipped.
    const double d0 = depth_of_coordinate(n[k]), d1 = depth_of_coordinate(n[k + 1]);
    const double shallow = std::min(d0, d1), deep = std::max(d0, d1);
    if (deep <= from || shallow >= to) continue;
    const double size = n[k + 1] - n[k];
    coarsest = std::max(coarsest, size);
    // Cells of a band are equal to its size up to round-off of the nodes' sums.
    if (size > axial_cell_ * (1.0 + 1e-9)) coarser_from = std::min(coarser_from, std::max(from, shallow));
  }
  c["coarsest"] = coarsest;
  c["coarser_from_depth"] = std::isfinite(coarser_from) ? JsonValue(coarser_from) : JsonValue();
  return c;
}

JsonValue PenetrationProbe::layer_holes(const FieldStore& pts) const {
  // Each layer in axial bins of the finest cell through its thickness as it was seeded (each point
  // in the slice it started in, wherever the layer has since moved: the jet's blast dishes a casing
  // by millimetres, and fixed bins would read the displaced plate as a wide hole): the wall at its
  // struck face (the entrance hole) and the narrowest wall through it (the hole a gauge passes).
  // No wall in a slice: the layer has gone from there (not measured).
  JsonValue holes = JsonValue::object();
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    const int bins = std::max(2, static_cast<int>(std::lround(layer_thickness_[k] / axial_cell_)));
    const std::vector<double> wall = wall_radii(lateral_points(pts, layers_[k], layer_face_[k], true), 0.0,
                                                layer_thickness_[k], bins, lateral_geometry_, {lateral_cell_});
    double narrowest = kInfinity, sum = 0.0;
    int walls = 0;
    JsonValue profile = JsonValue::array();
    for (double w : wall) {
      profile.push_back(std::isfinite(w) ? JsonValue(2.0 * w) : JsonValue());
      if (!std::isfinite(w)) continue;
      narrowest = std::min(narrowest, w);
      sum += w;
      ++walls;
    }
    JsonValue& h = holes[spec_.layers[k]];
    h = JsonValue::object();
    h["entrance_diameter"] = std::isfinite(wall.front()) ? JsonValue(2.0 * wall.front()) : JsonValue();
    h["min_diameter"] = std::isfinite(narrowest) ? JsonValue(2.0 * narrowest) : JsonValue();
    // The hole's shape through the layer: the entrance and the narrowest are single slices, and on a
    // finer grid the slices are thinner; the mean over the slices is the hole averaged through the
    // thickness, the same quantity at every cell size.
    h["mean_diameter"] = walls > 0 ? JsonValue(2.0 * sum / walls) : JsonValue();
    h["diameters"] = profile;
    h["perforated"] = std::isfinite(narrowest) && narrowest > 0.0;
    h["thickness"] = layer_thickness_[k];
    h["face_depth"] = depth_of_coordinate(layer_face_[k]);  // m, negative: above the target's face
    h["jet_behind"] = jet_behind(k);
  }
  return holes;
}

void PenetrationProbe::record_layer_exits(const FieldStore& pts, double front, double time, double scale) {
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    LayerExit& e = layer_exit_[k];
    if (e.reached || jet_lines_.empty() || front < depth_of_coordinate(layer_face_[k]) + layer_thickness_[k]) continue;
    e.reached = true;
    e.sample = t_.size();
    e.time = time;
    e.jet = measure_jet_remainder(pts, penetrator_, jet_lines_, axis_, direction_, scale);
  }
}

JsonValue PenetrationProbe::jet_behind(std::size_t k) const {
  if (spec_.formed_jet) return JsonValue();  // no segments whose consumption could be followed
  // Hydrodynamic erosion (thesis eq. 3.1-3.2, P = L sqrt(rho_p / rho_t)): a layer of thickness T
  // consumes T sqrt(rho_layer / rho_p) of jet, summed over the layers the jet has gone through
  // (those whose struck face is not below this one's).
  double hydro = 0.0;
  for (std::size_t j = 0; j < layers_.size(); ++j)
    if (depth_of_coordinate(layer_face_[j]) <= depth_of_coordinate(layer_face_[k]) && rho_p_ > 0 &&
        layer_density_[j] > 0)
      hydro += layer_thickness_[j] * std::sqrt(layer_density_[j] / rho_p_);
  JsonValue j = JsonValue::object();
  const LayerExit& e = layer_exit_[k];
  j["reached"] = e.reached;
  j["time"] = e.reached ? JsonValue(e.time) : JsonValue();
  j["consumed_length"] = e.reached ? JsonValue(e.jet.consumed_length) : JsonValue();
  j["remaining_length"] = e.reached ? JsonValue(e.jet.remaining_length) : JsonValue();
  j["tip_velocity"] = e.reached && e.jet.tip_segment >= 0 ? JsonValue(e.jet.tip_velocity) : JsonValue();
  j["tip_segment"] = e.reached ? JsonValue(static_cast<double>(e.jet.tip_segment)) : JsonValue();
  j["tip_initial_velocity"] = e.reached && e.jet.tip_segment >= 0
                                  ? JsonValue(jet_lines_[static_cast<std::size_t>(e.jet.tip_segment)].speed)
                                  : JsonValue();
  j["hydrodynamic_consumed_length"] = hydro;
  return j;
}

void PenetrationProbe::save_state(StateArchive& a, std::size_t samples) const {
  const auto first = [&](const std::vector<double>& v) {
    return std::vector<double>(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(std::min(samples, v.size())));
  };
  a.put("penetration.time", first(t_));
  a.put("penetration.depth", first(depth_));
  a.put("penetration.cavity", first(cavity_));
  // Per layer: sample (-1: not reached by the saved state), time, consumed, remaining, tip speed
  // and tip segment.
  std::vector<double> exits;
  for (const LayerExit& e : layer_exit_) {
    const bool kept = e.reached && e.sample <= samples;
    exits.insert(exits.end(), {kept ? static_cast<double>(e.sample) : -1.0, e.time, e.jet.consumed_length,
                               e.jet.remaining_length, e.jet.tip_velocity, static_cast<double>(e.jet.tip_segment)});
  }
  a.put("penetration.layer_exits", exits);
  a.put("penetration.kinetic", first(kinetic_));
  // The first sample with every segment in, if the saved state had it (-1: not yet).
  a.put_int("penetration.entered_sample",
            entered_sample_ >= 0 && static_cast<std::size_t>(entered_sample_) < samples ? entered_sample_ : -1);
}

void PenetrationProbe::load_state(const StateArchive& a) {
  t_ = a.reals("penetration.time");
  depth_ = a.reals("penetration.depth", t_.size());
  cavity_ = a.reals("penetration.cavity", t_.size());
  kinetic_ = a.reals("penetration.kinetic", t_.size());
  peak_kinetic_ = 0.0;
  for (const double e : kinetic_) peak_kinetic_ = std::max(peak_kinetic_, e);
  entered_sample_ = a.integer("penetration.entered_sample");
  // The state checkpointed was not spent, or the run would have ended there.
  spent_sample_ = -1;
  layer_exit_.assign(layers_.size(), LayerExit{});
  if (!a.has("penetration.layer_exits")) return;  // a checkpoint from before the record: none yet
  const std::vector<double>& r = a.reals("penetration.layer_exits", 6 * layers_.size());
  for (std::size_t k = 0; k < layers_.size(); ++k) {
    const double* q = &r[6 * k];
    if (q[0] < 0) continue;
    layer_exit_[k] = {true, static_cast<std::size_t>(q[0]), q[1], {q[2], q[3], q[4], static_cast<int>(q[5])}};
  }
}

}  // namespace ballista
