#include "points/explosive_lighting.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "geometry/grid_axes.hpp"
#include "geometry/seeding.hpp"
#include "materials/explosive_eos.hpp"
#include "points/program_burn.hpp"

namespace ballista {

Index light_explosives(const Scenario& sc, FieldStore& points, int ppc_override) {
  const DetonationSpec& det = sc.detonation;
  if (det.points.empty()) return 0;
  auto deck_error = [&](const std::string& key, const std::string& message) {
    throw DeckError(det.mark.file, det.mark.line, det.mark.column, "detonation" + (key.empty() ? "" : "." + key),
                    message);
  };
  // Lighting times count from t = 0; with preparation stages the charge would go off during them.
  if (!sc.stages.empty())
    deck_error("", "explosives with preparation stages are not supported yet: the lighting times count from t = 0, "
                   "not from the start of the main stage");
  // One detonation speed and one lattice spacing over every explosive body.
  double D = 0.0, spacing = 0.0;
  std::vector<char> is_explosive_material(sc.materials.size(), 0);
  for (size_t m = 0; m < sc.materials.size(); ++m) {
    const MaterialSpec& ms = sc.materials[m];
    if (ms.model != "explosive") continue;
    is_explosive_material[m] = 1;
    const double d = ms.params.at("detonation_speed");
    if (D > 0.0 && d != D)
      deck_error("", fmt::format("explosives with different detonation speeds ({} and {} m/s) are not supported by "
                                 "the program burn yet (one front speed)",
                                 D, d));
    D = d;
  }
  for (const BodySpec& b : sc.bodies) {
    int mi = -1;
    for (size_t m = 0; m < sc.materials.size(); ++m)
      if (sc.materials[m].name == b.material) mi = static_cast<int>(m);
    if (mi < 0 || !is_explosive_material[mi]) continue;
    if (b.activation_time > 0.0 || b.activation_stage > 0 || !b.segments.empty())
      deck_error("", "explosive body '" + b.name + "' has a later activation: not supported by the program burn");
    BodySpec seeded = b;
    if (ppc_override > 0) seeded.particles_per_cell = ppc_override;
    const double s = seed_spacing(seeded, sc.grid.cell_size);
    if (spacing > 0.0 && std::abs(s / spacing - 1.0) > 1e-12)
      deck_error("", "explosive bodies with different point spacings are not supported by the program burn yet");
    spacing = s;
  }
  const Index n = points.size();
  const auto* mat = points.ints(kMaterialIndex);
  const auto* x0 = points.view(kReferencePosition);
  std::vector<char> explosive(static_cast<size_t>(n), 0);
  for (Index p = 0; p < n; ++p) explosive[p] = is_explosive_material[static_cast<size_t>(mat[p])];
  // On a graded grid the points are as fine as the cells they were seeded in (particles_per_cell
  // per cell and axis): the charge is one lattice only if those cells are all squares of one size.
  // (The cells, not the points' half-sizes: a cut_lattice point at the surface is smaller.)
  if (sc.grid.graded()) {
    const int dim = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
    const GridAxes axes = build_grid_axes(sc.grid, dim);
    const auto* body = points.ints(kBodyIndex);
    double local = 0.0;
    for (Index p = 0; p < n; ++p) {
      if (!explosive[p]) continue;
      const BodySpec& b = sc.bodies[static_cast<size_t>(body[p])];
      const int ppc = ppc_override > 0 ? ppc_override : b.particles_per_cell;
      for (int a = 0; a < dim; ++a) {
        const double s = axes.effective_cell_size(a, x0[p], dim) / ppc;
        if (local == 0.0) local = s;
        if (std::abs(s / local - 1.0) > 1e-9)
          deck_error("", fmt::format("the explosive lies in cells of different sizes or shapes on the graded grid "
                                     "(point spacings {:.6g} and {:.6g} m near ({:.6g}, {:.6g}, {:.6g}) m): the program "
                                     "burn needs one lattice; put the charge inside one band of grid.refine along "
                                     "every axis, and inside or outside each patch",
                                     local, s, x0[p][0], x0[p][1], x0[p][2]));
      }
    }
    if (local > 0.0) spacing = local;
  }
  std::vector<Detonator> detonators;
  for (const DetonatorSpec& d : det.points) detonators.push_back({d.position, d.time});
  ProgramBurnOptions opt;
  opt.speed = D;
  opt.spacing = spacing;
  opt.radius_factor = det.edge_radius;
  opt.dim = sc.simulation.dimension == Dimension::ThreeD ? 3 : 2;
  ProgramBurnResult r;
  try {
    r = program_burn(x0, explosive.data(), n, detonators, opt);
  } catch (const Error& e) {
    deck_error("points", e.what());
  }
  if (r.unreachable > 0) {
    Index first = -1;
    for (Index p = 0; p < n && first < 0; ++p)
      if (explosive[p] && !std::isfinite(r.time[p])) first = p;
    deck_error("points", fmt::format("{} explosive points are cut off from every detonator by inert material or void "
                                     "(the first at ({:.6g}, {:.6g}, {:.6g}) m): add a detonator in that part of the "
                                     "charge",
                                     r.unreachable, x0[first][0], x0[first][1], x0[first][2]));
  }
  auto* t = points.real(kLightingTime);
  auto* tau = points.real(kBurnTime);
  Index lit = 0;
  for (Index p = 0; p < n; ++p)
    if (explosive[p]) {
      t[p] = r.time[p];
      tau[p] = det.burn_cells * spacing / D;
      ++lit;
    }
  return lit;
}

}  // namespace ballista
