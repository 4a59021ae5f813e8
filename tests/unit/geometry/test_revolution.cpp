// Solids of revolution (geometry/revolution.hpp; shapes cone, liner, revolution) against closed
// forms: Pappus volumes, signed distances, rejected outlines, membership in 3D, axisymmetric and
// plane-strain decks, and seeded volumes within the lattice bound (a charge with its liner cavity
// cut out included).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/field_store.hpp"
#include "deck/deck_reader.hpp"
#include "geometry/revolution.hpp"
#include "geometry/seeding.hpp"
#include "geometry/shape.hpp"
#include "materials/material.hpp"
#include "support/test_files.hpp"

namespace test_revolution {

using namespace ballista;
using std::numbers::pi;

namespace {

/// The liner of a 60 degree cone, 1 mm wall, 30 mm mouth: its volume by cones, Pappus-independent.
double liner_volume(double angle_deg, double t, double D) {
  const double a = 0.5 * angle_deg * pi / 180.0, R = 0.5 * D, H = R / std::tan(a);
  const double h_in = H - t / std::sin(a), r_in = R - t / std::cos(a);
  return pi / 3.0 * (R * R * H - r_in * r_in * h_in);
}

ShapeSpec revolution_spec(const std::string& type, const Outline& o, Vec3 center, int axis) {
  ShapeSpec s;
  s.type = type;
  s.center = center;
  s.axis = axis;
  s.outline = o;
  return s;
}

}  // namespace

TEST(Revolution, PappusVolumesOfConeLinerAndCylinder) {
  EXPECT_NEAR(outline_volume(cone_outline(0.02, 0.0, 0.05)), pi * 0.02 * 0.02 * 0.05 / 3.0, 1e-15);
  EXPECT_NEAR(outline_volume(cone_outline(0.0, 0.02, 0.05)), pi * 0.02 * 0.02 * 0.05 / 3.0, 1e-15);
  // Frustum: pi L (R^2 + R r + r^2) / 3.
  EXPECT_NEAR(outline_volume(cone_outline(0.02, 0.01, 0.05)), pi * 0.05 * (4e-4 + 2e-4 + 1e-4) / 3.0, 1e-15);
  EXPECT_NEAR(outline_volume({{0, 0}, {0.01, 0}, {0.01, 0.03}, {0, 0.03}}), pi * 1e-4 * 0.03, 1e-16);
  for (double angle : {40.0, 60.0, 90.0})
    EXPECT_NEAR(outline_volume(liner_outline(angle, 1e-3, 30e-3)), liner_volume(angle, 1e-3, 30e-3), 1e-15) << angle;
}

TEST(Revolution, SignedDistance) {
  const Outline box{{0, 0}, {0.01, 0}, {0.01, 0.03}, {0, 0.03}};
  EXPECT_NEAR(outline_depth(box, 0.004, 0.02), 0.004, 1e-15);   // nearest: the axis edge r = 0
  EXPECT_NEAR(outline_depth(box, 0.009, 0.015), 0.001, 1e-15);  // the outer edge
  EXPECT_NEAR(outline_depth(box, 0.012, 0.015), -0.002, 1e-15);
  EXPECT_NEAR(outline_depth(box, 0.013, 0.034), -0.005, 1e-15);  // to the corner (3, 4, 5)
  // The liner's mid-wall is half a wall inside; the cavity's axis is outside.
  const double a = pi / 6.0;  // 60 degree cone
  const Outline l = liner_outline(60.0, 1e-3, 30e-3);
  const double s = 0.01;  // a point on the outer surface, then 0.5 mm inwards along the normal
  const double r = s * std::sin(a) - 0.5e-3 * std::cos(a), z = s * std::cos(a) + 0.5e-3 * std::sin(a);
  EXPECT_NEAR(outline_depth(l, r, z), 0.5e-3, 1e-12);
  EXPECT_LT(outline_depth(l, 0.0, 0.01), 0.0);
}

TEST(Revolution, RejectedOutlines) {
  EXPECT_FALSE(outline_problem(liner_outline(60.0, 1e-3, 30e-3)));
  EXPECT_TRUE(outline_problem({{0, 0}, {1, 0}}));                       // two vertices
  EXPECT_TRUE(outline_problem({{0, 0}, {-1, 0}, {0, 1}}));              // r < 0
  EXPECT_TRUE(outline_problem({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));       // a bow tie
  EXPECT_TRUE(outline_problem({{0, 0}, {1, 0}, {2, 0}}));               // no area
  EXPECT_TRUE(outline_problem({{0, 0}, {2, 0}, {1, 0}, {1, 1}}));       // an edge folding back
  const auto why = outline_problem({{0, 0}, {1, 1}, {1, 0}, {0, 1}});
  EXPECT_NE(why->find("cross or touch"), std::string::npos) << *why;
}

TEST(Revolution, MembershipIn3dAxisymmetricAndPlaneStrain) {
  const ShapeSpec liner = revolution_spec("liner", liner_outline(60.0, 1e-3, 30e-3), {1.0, 2.0, 3.0}, 0);
  const double a = pi / 6.0, s = 0.02, r = s * std::sin(a) - 0.5e-3 * std::cos(a), z = s * std::cos(a) + 0.5e-3 * std::sin(a);
  // 3D, axis x: any azimuth at (z, r) is inside, the cavity's axis is not.
  for (double phi : {0.0, 1.0, 2.5, 4.0}) {
    const Vec3 x{1.0 + z, 2.0 + r * std::cos(phi), 3.0 + r * std::sin(phi)};
    EXPECT_TRUE(shape_contains(liner, x, 3)) << phi;
    EXPECT_NEAR(shape_depth(liner, x, 3), 0.5e-3, 1e-12);
  }
  EXPECT_FALSE(shape_contains(liner, Vec3{1.0 + 0.01, 2.0, 3.0}, 3));
  // Axisymmetric (axis y, centre on it): the (r, z) section.
  const ShapeSpec axi = revolution_spec("liner", liner_outline(60.0, 1e-3, 30e-3), {0.0, 0.01, 0.0}, 1);
  EXPECT_TRUE(shape_contains(axi, Vec3{r, 0.01 + z, 0.0}, 2));
  EXPECT_FALSE(shape_contains(axi, Vec3{r + 2e-3, 0.01 + z, 0.0}, 2));
  // Plane strain (axis y): the axial section, both sides of the axis line.
  const ShapeSpec plane = revolution_spec("liner", liner_outline(60.0, 1e-3, 30e-3), {0.05, 0.01, 0.0}, 1);
  EXPECT_TRUE(shape_contains(plane, Vec3{0.05 + r, 0.01 + z, 0.0}, 2));
  EXPECT_TRUE(shape_contains(plane, Vec3{0.05 - r, 0.01 + z, 0.0}, 2));
  // Bounds: the mouth's radius across, the cone's height along.
  Vec3 lo, hi;
  shape_bounds(liner, 3, lo, hi);
  EXPECT_NEAR(hi[0] - lo[0], 0.015 / std::tan(a), 1e-15);
  EXPECT_NEAR(hi[1] - 2.0, 0.015, 1e-15);
  // A point on the outer surface is inside (closed shapes, 1e-12 of the size).
  EXPECT_TRUE(shape_contains(axi, Vec3{0.005, 0.01 + 0.005 / std::tan(a), 0.0}, 2));
}

namespace {

struct SeededDeck {
  Scenario sc;
  FieldStore pts;
};

std::unique_ptr<SeededDeck> seed(const std::string& yaml) {
  auto s = std::make_unique<SeededDeck>();
  s->sc = parse_deck(yaml, "revolution_test.yaml");
  std::vector<std::unique_ptr<Material>> mats;
  for (const auto& m : s->sc.materials) mats.push_back(find_material(m.model)->create(m.name, m.params));
  declare_point_fields(s->pts);
  for (const auto& m : mats) m->declare_fields(s->pts);
  std::int64_t next_id = 0;
  for (size_t b = 0; b < s->sc.bodies.size(); ++b)
    seed_body(s->sc.bodies[b], static_cast<int>(b), 0, *mats[0], s->sc.grid, s->sc.simulation.dimension, s->pts,
              next_id);
  return s;
}

double body_volume(const FieldStore& p, int body) {
  const auto* v = p.real("volume0");
  const auto* b = p.ints("body");
  double sum = 0.0;
  for (Index i = 0; i < p.size(); ++i)
    if (b[i] == body) sum += v[i];
  return sum;
}

std::string charge_deck(int ppc) {
  return "simulation: {dimension: axisymmetric, end_time: 1.0e-6}\n"
         "grid: {lower: [0, -0.002], upper: [0.03, 0.05], cell_size: 0.5e-3}\n"
         "materials:\n  m: {model: linear_elastic, density: 2000, youngs_modulus: 1.0e9, poisson_ratio: 0.25}\n"
         "bodies:\n"
         "  - name: charge\n    material: m\n    particles_per_cell: " + std::to_string(ppc) + "\n"
         "    shape: {type: cylinder, center: [0, 0], axis: y, radius: 16.0e-3, length: 36.0e-3}\n"
         "    cutouts: [{type: cone, center: [0, 10.0e-3], axis: y, radius: 0, top_radius: 15.0e-3, length: 25.98e-3}]\n"
         "  - name: liner\n    material: m\n    particles_per_cell: " + std::to_string(ppc) + "\n"
         "    shape: {type: liner, center: [0, 10.0e-3], axis: y, angle: 60, thickness: 1.0e-3, diameter: 30.0e-3}\n";
}

}  // namespace

// A shaped charge's section: the liner (a 1 mm shell) and the explosive around its cavity. The
// seeded volume per radian, the sum of r dA over the lattice points, misses at most the band of half
// a point's diagonal around the boundary: bound = sqrt2 dx/2 x (integral of r ds over the outline +
// a corner term per vertex). It shrinks with the points per cell; at 8 per cell (a 1 mm wall 16 points
// thick) it is informative.
TEST(Revolution, SeededChargeAndLinerVolumesConverge) {
  const Outline liner = liner_outline(60.0, 1e-3, 30e-3);
  const double liner_exact = outline_volume(liner) / (2.0 * pi);
  const double cyl = 0.5 * 16e-3 * 16e-3 * 36e-3;
  const double cone = outline_volume(cone_outline(0.0, 15e-3, 25.98e-3)) / (2.0 * pi);
  auto r_ds = [](const Outline& o) {
    double s = 0.0;
    for (size_t i = 0, j = o.size() - 1; i < o.size(); j = i++)
      s += 0.5 * (o[i][0] + o[j][0]) * std::hypot(o[i][0] - o[j][0], o[i][1] - o[j][1]);
    return s;
  };
  double last_error = 1.0;
  for (int ppc : {2, 4, 8}) {
    const auto s = seed(charge_deck(ppc));
    const double dx = 0.5e-3 / ppc, band = std::sqrt(2.0) * 0.5 * dx;
    const double liner_bound = band * (r_ds(liner) + 4 * 15e-3 * band);
    const double err = std::abs(body_volume(s->pts, 1) - liner_exact);
    EXPECT_LT(err, liner_bound) << ppc;
    if (ppc == 8) {
      EXPECT_LT(liner_bound, 0.2 * liner_exact);  // informative: catches a wrong r weight or cell volume
    }
    last_error = err;
    // The charge: the cylinder without the cone (the cutout), within the same kind of bound.
    const double charge_exact = cyl - cone;
    const double charge_bound = band * (r_ds(cone_outline(0.0, 15e-3, 25.98e-3)) + 16e-3 * 36e-3 + 0.5 * 16e-3 * 16e-3 * 2 +
                                        8 * 16e-3 * band);
    EXPECT_LT(std::abs(body_volume(s->pts, 0) - charge_exact), charge_bound) << ppc;
  }
  EXPECT_LT(last_error, 0.02 * liner_exact);
}

TEST(Revolution, DeckKeysAndErrors) {
  const Scenario s = parse_deck(charge_deck(2), "charge.yaml");
  EXPECT_EQ(s.bodies[1].shape.type, "liner");
  EXPECT_EQ(s.bodies[1].shape.outline.size(), 4u);
  EXPECT_EQ(s.bodies[0].cutouts.at(0).type, "cone");
  auto error_of = [](const std::string& deck) {
    try {
      parse_deck(deck, "bad.yaml");
    } catch (const DeckError& e) {
      return std::string(e.key_path()) + ": " + e.what();
    }
    return std::string("no error");
  };
  auto with = [](std::string d, const std::string& a, const std::string& b) { return d.replace(d.find(a), a.size(), b); };
  const std::string thick = error_of(with(charge_deck(2), "thickness: 1.0e-3", "thickness: 13.0e-3"));
  EXPECT_NE(thick.find("bodies.1.shape.thickness"), std::string::npos) << thick;
  EXPECT_NE(thick.find("cos(angle / 2)"), std::string::npos) << thick;
  const std::string angle = error_of(with(charge_deck(2), "angle: 60", "angle: 180"));
  EXPECT_NE(angle.find("bodies.1.shape.angle"), std::string::npos) << angle;
  const std::string axis = error_of(with(charge_deck(2), "axis: y, angle", "axis: x, angle"));
  EXPECT_NE(axis.find("expected axis y in an axisymmetric deck"), std::string::npos) << axis;
  const std::string bowtie = error_of(with(charge_deck(2),
                                           "{type: liner, center: [0, 10.0e-3], axis: y, angle: 60, thickness: 1.0e-3, "
                                           "diameter: 30.0e-3}",
                                           "{type: revolution, center: [0, 0.01], axis: y, outline: [[0, 0], [0.01, "
                                           "0.01], [0.01, 0], [0, 0.01]]}"));
  EXPECT_NE(bowtie.find("bodies.1.shape.outline"), std::string::npos) << bowtie;
  EXPECT_NE(bowtie.find("cross or touch"), std::string::npos) << bowtie;
  const std::string row = error_of(with(charge_deck(2),
                                        "{type: liner, center: [0, 10.0e-3], axis: y, angle: 60, thickness: 1.0e-3, "
                                        "diameter: 30.0e-3}",
                                        "{type: revolution, center: [0, 0.01], axis: y, outline: [[0, 0], [0.01], [0, "
                                        "0.01]]}"));
  EXPECT_NE(row.find("bodies.1.shape.outline.1"), std::string::npos) << row;
  // A pressure needs named faces: a liner has none (its "outer" would be read as a cylinder's).
  const std::string pressure = error_of(charge_deck(2) + "loads:\n  - {type: pressure, body: liner, surface: outer, "
                                                         "pressure: 1.0e6}\n");
  EXPECT_NE(pressure.find("loads.0.body"), std::string::npos) << pressure;
  EXPECT_NE(pressure.find("body 'liner' is a liner"), std::string::npos) << pressure;
}

}  // namespace test_revolution
