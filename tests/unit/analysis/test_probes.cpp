// Probes, made through the probe registry (points/probe_registry.hpp) as the run loop makes them,
// on hand-made point sets whose answers follow from the definitions of the probe kinds in
// analysis/*_probe.cpp: domains are x_p + F_p (+-a, +-b, +-c) with (a, b, c) = half_size.
// All inputs are short binary fractions, so most expected values are exact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "points/probe_registry.hpp"

namespace test_probes {

using namespace ballista;

namespace {

struct Pt {
  int body;
  Vec3 x;
  Vec3 half;
  Mat3 F = Mat3::identity();
  double eqps = 0.0;
};

FieldStore make(const std::vector<Pt>& pts) {
  FieldStore s;
  s.add_int("body", 1, "1");
  s.add_real("x", 3, "m");
  s.add_real("F", 9, "1");
  s.add_real("half_size", 3, "m");
  s.add_real("eqps", 1, "1");
  s.add_real("v", 3, "m/s");
  s.resize(static_cast<Index>(pts.size()));
  for (size_t i = 0; i < pts.size(); ++i) {
    s.ints("body")[i] = pts[i].body;
    s.view<Vec3>("x")[i] = pts[i].x;
    s.view<Mat3>("F")[i] = pts[i].F;
    s.view<Vec3>("half_size")[i] = pts[i].half;
    s.real("eqps")[i] = pts[i].eqps;
  }
  return s;
}

/// A probe with the parameters the deck reader would fill (defaults of the optional ones).
ProbeSpec probe(const std::string& type, int axis = 1) {
  ProbeSpec p;
  p.name = type;
  p.type = type;
  p.params["axis"] = axis;
  p.params["plane"] = 0.0;
  p.params["distance"] = 0.0;
  p.vectors["center"] = Vec3{};
  return p;
}

/// The probe made by the registry for the body with this index (-1: every body) of a deck with
/// bodies b0 .. b3.
std::unique_ptr<Probe> make_probe(ProbeSpec p, int body) {
  Scenario sc;
  for (int b = 0; b < 4; ++b) {
    BodySpec body;
    body.name = "b" + std::to_string(b);
    sc.bodies.push_back(body);
  }
  p.params.choices["body"] = body < 0 ? "" : "b" + std::to_string(body);
  sc.probes = {p};
  return std::move(make_probes(sc).front());
}

double eval(const ProbeSpec& p, int body, const FieldStore& s, Dimension dim = Dimension::ThreeD,
            const EnergyTotals& e = {}) {
  const Communicator comm;
  return make_probe(p, body)->value(ProbeContext{s, e, dim, comm});
}

Mat3 shear_xy(double g) {  // x += g y
  Mat3 F = Mat3::identity();
  F(0, 1) = g;
  return F;
}

}  // namespace

TEST(Probes, ExtentUsesTheDeformedDomainCorners) {
  Mat3 F = shear_xy(0.5);
  F(1, 1) = 2.0;
  // Particle 0: x-extent of its domain 2 (a + 0.5 b), y-extent 2 * 2 b, z-extent 2 c.
  const FieldStore s = make({{0, {{1.0, 2.0, 3.0}}, {{0.125, 0.25, 0.375}}, F},
                             {1, {{5.0, 0.0, 0.0}}, {{0.125, 0.125, 0.125}}}});
  EXPECT_DOUBLE_EQ(eval(probe("extent", 0), 0, s), 2 * (0.125 + 0.5 * 0.25));
  EXPECT_DOUBLE_EQ(eval(probe("extent", 1), 0, s), 2 * 2 * 0.25);
  EXPECT_DOUBLE_EQ(eval(probe("extent", 2), 0, s), 2 * 0.375);
  // All bodies: from the lowest corner of particle 0 to the highest of particle 1.
  EXPECT_DOUBLE_EQ(eval(probe("extent", 0), -1, s), (5.0 + 0.125) - (1.0 - 0.125 - 0.5 * 0.25));
  EXPECT_DOUBLE_EQ(eval(probe("extent", 1), -1, s), (2.0 + 0.5) - (0.0 - 0.125));
  // Body 1 alone.
  EXPECT_DOUBLE_EQ(eval(probe("extent", 0), 1, s), 0.25);
}

TEST(Probes, ExtentOfARotatedDomain) {
  // 90 degrees about z: the domain's x-extent is 2b, its y-extent 2a.
  const Mat3 R = rotation_about({{0.0, 0.0, 1.0}}, std::numbers::pi / 2);
  const FieldStore s = make({{0, {{0.0, 0.0, 0.0}}, {{0.125, 0.5, 0.25}}, R}});
  EXPECT_NEAR(eval(probe("extent", 0), 0, s), 1.0, 1e-15);
  EXPECT_NEAR(eval(probe("extent", 1), 0, s), 0.25, 1e-15);
}

TEST(Probes, TwoDimensionalDomainsHaveFourCornersInThePlane) {
  // In 2D the third half-size and F's out-of-plane column must not enter the in-plane extent.
  Mat3 F = Mat3::identity();
  F(0, 2) = 1.0;
  const FieldStore s = make({{0, {{1.0, 1.0, 0.0}}, {{0.25, 0.125, 7.0}}, F}});
  EXPECT_DOUBLE_EQ(eval(probe("extent", 0), 0, s, Dimension::PlaneStrain), 0.5);
  EXPECT_DOUBLE_EQ(eval(probe("extent", 1), 0, s, Dimension::Axisymmetric), 0.25);
}

TEST(Probes, MaxRadiusAroundAnAxisNearAPlane) {
  ProbeSpec p = probe("max_radius", 1);  // axis y
  p.params["plane"] = 0.0;
  p.params["distance"] = 0.0625;
  const FieldStore s = make({
      {0, {{0.5, 0.03125, 0.0}}, {{0.125, 0.125, 0.125}}},   // corners reach r^2 = 0.625^2 + 0.125^2
      {0, {{0.25, -0.0625, 0.25}}, {{0.125, 0.125, 0.125}}},  // exactly at the distance: counts; r = 0.375 sqrt 2
      {0, {{2.0, 0.25, 0.0}}, {{0.125, 0.125, 0.125}}},      // too far from the plane: ignored
      {1, {{4.0, 0.0, 0.0}}, {{0.125, 0.125, 0.125}}},       // other body
  });
  EXPECT_DOUBLE_EQ(eval(p, 0, s), std::sqrt(0.625 * 0.625 + 0.125 * 0.125));
  EXPECT_DOUBLE_EQ(eval(p, -1, s), std::sqrt(4.125 * 4.125 + 0.125 * 0.125));
  // Axis through another point: centre (0.5, *, 0) makes particle 1 the farthest of body 0.
  p.vectors["center"] = {{0.5, 123.0, 0.0}};  // the position along the axis does not matter
  EXPECT_DOUBLE_EQ(eval(p, 0, s), std::sqrt(0.375 * 0.375 + 0.375 * 0.375));
  // A plane elsewhere: no particle of body 0 qualifies -> NaN.
  p.params["plane"] = 10.0;
  EXPECT_TRUE(std::isnan(eval(p, 0, s)));
}

TEST(Probes, MaxRadiusInTwoDimensions) {
  // Axisymmetric (axis y): the radius is x. Plane strain with axis x: the distance is |y - c_y|.
  ProbeSpec p = probe("max_radius", 1);
  p.params["distance"] = 0.5;
  const FieldStore s = make({{0, {{0.75, 0.25, 0.0}}, {{0.125, 0.125, 0.0}}},
                             {0, {{0.25, -0.375, 0.0}}, {{0.125, 0.125, 0.0}}}});
  EXPECT_DOUBLE_EQ(eval(p, 0, s, Dimension::Axisymmetric), 0.875);
  ProbeSpec q = probe("max_radius", 0);
  q.params["distance"] = 1.0;
  q.vectors["center"] = {{0.0, 0.125, 0.0}};
  EXPECT_DOUBLE_EQ(eval(q, 0, s, Dimension::PlaneStrain), 0.625);  // |-0.375 - 0.125 - 0.125|
}

TEST(Probes, FieldMaxOverABody) {
  Pt a{0, {{0.0, 0.0, 0.0}}, {{0.1, 0.1, 0.1}}};
  Pt b = a, c = a;
  a.eqps = -3.0;
  b.eqps = -2.0;  // the largest of body 0 is negative: must not be clamped at 0
  c.body = 1;
  c.eqps = 5.0;
  const FieldStore s = make({a, b, c});
  ProbeSpec p = probe("field_max");
  p.params.choices["field"] = "eqps";
  EXPECT_EQ(eval(p, 0, s), -2.0);
  EXPECT_EQ(eval(p, 1, s), 5.0);
  EXPECT_EQ(eval(p, -1, s), 5.0);
  EXPECT_TRUE(std::isnan(eval(p, 2, s)));  // a body with no particles
}

TEST(Probes, NothingQualifiesGivesNan) {
  const FieldStore empty = make({});
  EXPECT_TRUE(std::isnan(eval(probe("extent", 0), -1, empty)));
  ProbeSpec r = probe("max_radius", 2);
  r.params["distance"] = 1.0;
  EXPECT_TRUE(std::isnan(eval(r, -1, empty)));
  ProbeSpec f = probe("field_max");
  f.params.choices["field"] = "eqps";
  EXPECT_TRUE(std::isnan(eval(f, -1, empty)));
  const FieldStore one = make({{0, {{0.0, 0.0, 0.0}}, {{0.1, 0.1, 0.1}}}});
  EXPECT_TRUE(std::isnan(eval(probe("extent", 0), 3, one)));
}

TEST(Probes, EnergyReturnsTheRequestedTotal) {
  EnergyTotals e;
  e.kinetic = 1.5;
  e.internal = 2.25;
  e.plastic = 0.5;
  e.external = 4.0;
  e.removed_energy = 0.125;
  const FieldStore s = make({});
  ProbeSpec p = probe("energy");
  const std::pair<const char*, double> expected[] = {
      {"kinetic", 1.5}, {"internal", 2.25}, {"plastic", 0.5}, {"external", 4.0},
      {"total", 1.5 + 2.25 + 0.125 - 4.0}};  // kinetic + internal + removed - external
  for (const auto& [field, value] : expected) {
    p.params.choices["field"] = field;
    EXPECT_EQ(eval(p, -1, s, Dimension::ThreeD, e), value) << field;
  }
}

TEST(Probes, ValidationRejectsNonScalarOrMissingFields) {
  const FieldStore s = make({});
  ProbeSpec p = probe("field_max");
  p.params.choices["field"] = "eqps";
  EXPECT_NO_THROW(make_probe(p, -1)->check(s));
  p.params.choices["field"] = "v";  // a vector
  EXPECT_THROW(make_probe(p, -1)->check(s), DeckError);
  p.params.choices["field"] = "body";  // an integer field
  EXPECT_THROW(make_probe(p, -1)->check(s), DeckError);
  p.params.choices["field"] = "no_such_field";
  try {
    make_probe(p, -1)->check(s);
    FAIL() << "expected a DeckError";
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("eqps"), std::string::npos) << "lists the scalar fields: " << e.what();
  }
  // Other probe types do not need a field.
  EXPECT_NO_THROW(make_probe(probe("extent"), -1)->check(s));
}

TEST(Probes, UnknownTypeIsAnError) {
  const FieldStore s = make({{0, {{0.0, 0.0, 0.0}}, {{0.1, 0.1, 0.1}}}});
  EXPECT_THROW(eval(probe("median"), -1, s), Error);
}

// radial_velocity: sum m (v . e_r) / sum m about the axis through `center`. Points of a ring about
// z moving radially at 3 m/s plus a common axial 5 m/s (no radial part) and one tangential
// (no radial part): the mean is 3 m/s weighted by mass.
TEST(Probes, RadialVelocityAboutAnAxis) {
  ProbeSpec p = probe("radial_velocity", 2);  // axis z
  FieldStore s = make({
      {0, {{1.0, 0.0, 0.5}}, {}},
      {0, {{0.0, -2.0, 0.0}}, {}},
      {0, {{-0.5, 0.0, 7.0}}, {}},
      {1, {{4.0, 0.0, 0.0}}, {}},  // other body: moving inwards
  });
  s.add_real("mass", 1, "kg");
  const double m[4] = {1.0, 2.0, 1.0, 1.0};
  const Vec3 v[4] = {{{3.0, 0.0, 5.0}}, {{0.0, -3.0, 5.0}}, {{0.0, 4.0, 5.0}}, {{-1.0, 0.0, 0.0}}};
  for (int i = 0; i < 4; ++i) {
    s.real("mass")[i] = m[i];
    s.view<Vec3>("v")[i] = v[i];
  }
  EXPECT_DOUBLE_EQ(eval(p, 0, s), (3.0 * 1.0 + 3.0 * 2.0 + 0.0) / 4.0);
  EXPECT_DOUBLE_EQ(eval(p, 1, s), -1.0);
  // An axis through x = 4: body 1's point is on it (no direction), so it has no value.
  p.vectors["center"] = {{4.0, 0.0, 0.0}};
  EXPECT_TRUE(std::isnan(eval(p, 1, s)));
}

TEST(Probes, MaxAndMinVelocityAlongAnAxis) {
  FieldStore s = make({{0, {}, {}}, {0, {}, {}}, {0, {}, {}}, {1, {}, {}}});
  const Vec3 v[4] = {{{9.0, 2.0, 0.0}}, {{0.0, 5.5, 0.0}}, {{0.0, -3.0, 0.0}}, {{0.0, 8.0, 0.0}}};
  for (int i = 0; i < 4; ++i) s.view<Vec3>("v")[i] = v[i];
  EXPECT_EQ(eval(probe("max_velocity", 1), 0, s), 5.5);  // the tip; body 1 and the x component not counted
  EXPECT_EQ(eval(probe("min_velocity", 1), 0, s), -3.0);
  EXPECT_EQ(eval(probe("max_velocity", 1), -1, s), 8.0);  // every body
  EXPECT_EQ(eval(probe("max_velocity", 0), 0, s), 9.0);
  EXPECT_TRUE(std::isnan(eval(probe("max_velocity", 1), 2, s)));  // no point: NaN
}

}  // namespace test_probes
