#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <set>

#include "material_driver.hpp"
#include "materials/strain_increment.hpp"

namespace test_material_adapter {

using namespace ballista;
using namespace ballista::test;

namespace {
bool same_bits(const Mat3& a, const Mat3& b) { return std::memcmp(a.a, b.a, sizeof a.a) == 0; }
}  // namespace

// The three models register themselves under their deck names with their parameters.
TEST(MaterialAdapter, ModelsAreRegistered) {
  std::set<std::string> names;
  for (const MaterialFactory& f : material_registry()) {
    names.insert(f.model);
    EXPECT_FALSE(f.description.empty()) << f.model;
    EXPECT_NE(f.create, nullptr) << f.model;
  }
  for (const char* m : {"linear_elastic", "neo_hookean", "j2_plasticity"}) {
    EXPECT_TRUE(names.count(m)) << m;
    const MaterialFactory* f = find_material(m);
    ASSERT_NE(f, nullptr) << m;
    EXPECT_EQ(f->model, m);
    bool has_density = false;
    for (const ParamSpec& s : f->params) has_density |= s.name == "density";
    EXPECT_TRUE(has_density) << m;
  }
  EXPECT_EQ(find_material("no_such_model"), nullptr);
  const auto mat = make_material("j2_plasticity", j2_steel_values());
  EXPECT_EQ(mat->name(), "test_j2_plasticity");
  EXPECT_STREQ(mat->model(), "j2_plasticity");
  EXPECT_EQ(mat->density(), 7800.0);
}

// declare_fields adds the model's state fields (name, unit, initial value), is idempotent and
// leaves other fields alone.
TEST(MaterialAdapter, DeclaresStateFields) {
  const auto mat = make_material("j2_plasticity", j2_steel_values());
  const auto specs = mat->state_fields();
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_EQ(specs[0].name, "eqps");
  FieldStore st;
  st.add_real("mass", 1, "kg");
  st.resize(3);
  st.real("mass")[1] = 2.5;
  mat->declare_fields(st);
  mat->declare_fields(st);  // idempotent
  ASSERT_TRUE(st.has("eqps"));
  EXPECT_EQ(st.info("eqps").unit, "1");
  EXPECT_EQ(st.info("eqps").ncomp, 1);
  EXPECT_EQ(st.fields().size(), 2u);
  for (Index p = 0; p < 3; ++p) EXPECT_EQ(st.real("eqps")[p], 0.0);
  EXPECT_EQ(st.real("mass")[1], 2.5);
  // Models without state declare nothing.
  FieldStore st2;
  make_material("linear_elastic", elastic_kg(1, 1, 1))->declare_fields(st2);
  EXPECT_TRUE(st2.fields().empty());
}

// A batch over a subset of the points updates exactly those points: stress, R, state and
// plastic work of the others are left bit-for-bit unchanged.
TEST(MaterialAdapter, BatchTouchesOnlyItsPoints) {
  const Index n = 7;
  PointDriver d("j2_plasticity", j2_steel_values(), n);
  const Mat3 sentinel{{1, 2, 3, 4, 5, 6, 7, 8, 9}};
  for (Index p = 0; p < n; ++p) {
    d.stress(p) = sentinel;
    d.state("eqps", p) = 0.125;
    d.plastic_work(p) = -1.0;
    d.set_dt(1e-3);
    d.set_F(p, Mat3::diag(1.01, 1.0, 1.0));  // large enough to yield
  }
  const std::vector<Index> subset{1, 4, 5};
  d.step(1e-3, subset);
  for (Index p = 0; p < n; ++p) {
    const bool in = p == 1 || p == 4 || p == 5;
    SCOPED_TRACE("point " + std::to_string(p));
    if (in) {
      EXPECT_FALSE(same_bits(d.stress(p), sentinel));
      EXPECT_GT(d.state("eqps", p), 0.125);
      EXPECT_GT(d.plastic_work(p), 0.0);
    } else {
      EXPECT_TRUE(same_bits(d.stress(p), sentinel));
      EXPECT_EQ(d.state("eqps", p), 0.125);
      EXPECT_EQ(d.plastic_work(p), -1.0);
      EXPECT_TRUE(same_bits(d.R(p), Mat3::identity()));
    }
  }
  // A null plastic_work pointer is allowed.
  MaterialBatch b;
  b.points = subset.data();
  b.count = 1;
  b.F_old = d.store().view<Mat3>("F_old");
  b.F_new = d.store().view<Mat3>("F");
  b.L = d.store().view<Mat3>("L");
  b.R = d.store().view<Mat3>("R");
  b.stress = d.store().view<Mat3>("stress");
  b.store = &d.store();
  b.dt = 1e-3;
  EXPECT_NO_THROW(d.material().update(b));
}

// The adapter stores the polar rotation of F_new in R and hands the kernel D_bar = R^T D R with D dt
// the midpoint increment sym(G (I + G/2)^-1), G = dt L (Hughes & Winget 1980): for F = Q diag(1+e,
// 1, 1) reached in one step from F = Q (R_old = Q), R_new = Q and the linear-elastic stress is
// Q diag(M d, lambda d, lambda d) Q^T with d = e/(1 + e/2) = 2 (lambda - 1)/(lambda + 1) (not e:
// the two differ by e^2/2 = 5e-9, 5e-5 relative). Tolerance 1e-10: forming F_{n+1} F_n^{-1} - I
// loses digits to cancellation, 1e-16/e = 1e-12.
TEST(MaterialAdapter, RotationAndUnrotatedRate) {
  const double K = 10e9, G = 6e9, M = K + 4 * G / 3, lam = K - 2 * G / 3, e = 1e-4;
  const double dm = e / (1 + 0.5 * e);
  PointDriver d("linear_elastic", elastic_kg(1000, K, G));
  const Mat3 Q = rotation_about(Vec3{{0.0, 0.6, 0.8}}, 1.3);
  d.F() = Q;
  d.R() = Q;
  d.advance(Q * Mat3::diag(1 + e, 1, 1), 1e-6);
  EXPECT_LT(frobenius(d.R() - Q), 1e-14);
  EXPECT_LT(rel_diff(d.stress(), rotate(Q, Mat3::diag(M * dm, lam * dm, lam * dm))), 1e-10);
  EXPECT_GT(rel_diff(d.stress(), rotate(Q, Mat3::diag(M * e, lam * e, lam * e))), 1e-5);  // not sym(L) dt
}

// The midpoint increment (materials/strain_increment.hpp) on random increments G (|G| ~ 0.1):
// equals sym(2 (dF - I)(dF + I)^-1), dF = I + G (the two forms are algebraically equal: 1e-14 of
// |G|, round-off of a 3x3 inverse); differs from sym(G) by O(|G|^2) (the leading term is
// -sym(G^2)/2, so the remainder after it is O(|G|^3): < |G|^3 checked); is inverted by
// spin_free_step_for_increment (symmetric eps -> dF symmetric, and back to eps to 1e-15).
TEST(StrainIncrement, MidpointFormsAndInverse) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (int trial = 0; trial < 50; ++trial) {
    Mat3 G;
    for (double& a : G.a) a = u(rng);
    const Mat3 I = Mat3::identity();
    const Mat3 dF = I + G;
    const Mat3 m = midpoint_strain_increment(G);
    const double g = frobenius(G);
    EXPECT_LT(frobenius(m - sym(2.0 * (dF - I) * inverse(dF + I))), 1e-14 * g) << trial;
    EXPECT_LT(frobenius(m - (sym(G) - 0.5 * sym(G * G))), g * g * g) << trial;
    const Mat3 eps = sym(G);
    const Mat3 S = spin_free_step_for_increment(eps);
    EXPECT_LT(frobenius(S - transpose(S)), 1e-16) << trial;
    EXPECT_LT(frobenius(midpoint_strain_increment(S - I) - eps), 1e-15) << trial;
  }
}

// A rigid rotation step has zero midpoint strain increment (the Cayley transform of a rotation is
// skew), however large the step: from a prestressed state, a step F -> Q F with Q a 0.5 rad
// rotation leaves the unrotated stress unchanged to round-off (1e-12 relative) and turns the spatial
// stress with Q. With sym(L) dt the step would add (cos 0.5 - 1) = -0.12 of strain in the plane.
TEST(MaterialAdapter, RigidRotationStepIsStrainFree) {
  PointDriver d("linear_elastic", elastic_kg(1000, 10e9, 6e9));
  const Mat3 F1{{1.001, 0.0003, 0, 0.0002, 0.9995, 0.0001, 0, 0.0004, 1.0007}};
  d.advance(F1, 1e-6);
  const Mat3 sb = d.stress_bar(), s = d.stress();
  const Mat3 Q = rotation_about(Vec3{{0.36, 0.48, 0.8}}, 0.5);
  d.advance(Q * F1, 1e-6);
  EXPECT_LT(rel_diff(d.stress_bar(), sb), 1e-12);
  EXPECT_LT(rel_diff(d.stress(), rotate(Q, s)), 1e-12);
}

// Results do not depend on the number of threads (each point is independent): bitwise equal.
TEST(MaterialAdapter, ThreadCountIndependent) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  const Index n = 5000;
  std::vector<Mat3> F(n);
  for (auto& f : F) {
    f = Mat3::identity();
    for (double& a : f.a) a += u(rng);
  }
  auto run = [&](int threads) {
    const int saved = max_threads();
    set_threads(threads);
    PointDriver d("j2_plasticity", j2_steel_values(), n);
    d.set_dt(1e-6);
    for (Index p = 0; p < n; ++p) d.set_F(p, F[p]);
    d.step(1e-6);
    set_threads(saved);
    std::vector<Mat3> s(n);
    for (Index p = 0; p < n; ++p) s[p] = d.stress(p);
    return s;
  };
  const auto s1 = run(1), s4 = run(4);
  for (Index p = 0; p < n; ++p) ASSERT_TRUE(same_bits(s1[p], s4[p])) << p;
}

// Parameter errors name the deck key.
TEST(MaterialAdapter, ParamErrors) {
  const MaterialFactory* f = find_material("neo_hookean");
  ASSERT_NE(f, nullptr);
  try {
    f->create("m", {{"density", 1.0}, {"youngs_modulus", 1.0}, {"poisson_ratio", 0.3}, {"bulk_modulus", 1.0}, {"shear_modulus", 1.0}});
    ADD_FAILURE() << "both elastic pairs accepted";
  } catch (const ParamError& e) {
    EXPECT_EQ(e.param(), "bulk_modulus");
  }
  EXPECT_THROW(f->create("m", {{"density", 1.0}, {"bulk_modulus", 1.0}}), ParamError);
  EXPECT_THROW(f->create("m", {{"density", 1.0}}), ParamError);
}

// Hyperelastic models provide the initial stress of a prestrained point; hypoelastic ones give 0.
TEST(MaterialAdapter, InitialStress) {
  const Mat3 F{{1.1, 0.05, 0, 0, 0.95, 0.02, 0.01, 0, 1.02}};
  const auto nh = make_material("neo_hookean", elastic_kg(1, 3, 2));
  const double lam = 3 - 4.0 / 3.0, mu = 2, J = det(F);
  Mat3 ref = (mu / J) * (F * transpose(F) - Mat3::identity());
  for (int i = 0; i < 3; ++i) ref(i, i) += lam * std::log(J) / J;
  EXPECT_LT(rel_diff(nh->initial_stress(F), ref), 1e-13);
  for (double x : make_material("linear_elastic", elastic_kg(1, 3, 2))->initial_stress(F).a) EXPECT_EQ(x, 0.0);
  for (double x : make_material("j2_plasticity", j2_steel_values())->initial_stress(F).a) EXPECT_EQ(x, 0.0);
}

}  // namespace test_material_adapter
