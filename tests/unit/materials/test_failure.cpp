// Failure criteria (thesis seed 000 §6.4, eq. 6.5-6.10): each one triggers at its analytic point,
// damage evolves as its closed form, and impossible combinations are rejected when the material
// is made. Erosion itself is tested in test_erosion.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "material_driver.hpp"
#include "materials/failure.hpp"
#include "test_failure_models.hpp"

namespace test_failure {

using namespace ballista;
using namespace ballista::test;

namespace {

ParamValues with_failure(ParamValues v, const std::string& criterion, const std::string& erosion = "none") {
  v.choices["failure.criterion"] = criterion;
  v.choices["failure.erosion"] = erosion;
  return v;
}

/// Runs `steps` steps of point 0 (F = I: the scripted models ignore the kinematics) and calls
/// check(n, damage, failed) after step n = 1..steps.
void run_scripted(PointDriver& d, int steps, double dt, const std::function<void(int, double, double)>& check) {
  for (int n = 1; n <= steps; ++n) {
    d.advance(Mat3::identity(), dt);
    check(n, d.state(kDamageField), d.state(kFailedField));
  }
}

/// First step n >= 1 at which n * increment >= threshold, with a check that the threshold is not
/// within round-off of a step (the tests compare an accumulated sum against it).
int first_step_reaching(double threshold, double increment) {
  const double x = threshold / increment;
  const double frac = x - std::floor(x);
  EXPECT_GT(std::min(frac, 1.0 - frac), 1e-6) << "threshold too close to a step: pick other constants";
  return static_cast<int>(std::ceil(x));
}

// Johnson-Cook damage constants of the order of Johnson & Cook's (1985, Table 2) 4340 steel.
constexpr double kD1 = 0.05, kD2 = 3.44, kD3 = -2.12, kD4 = 0.002, kD5 = 0.61;

ParamValues jc_values(double s11, double s22, double s33, double rate, double rate0, double tstar) {
  ParamValues v{{"stress_11", s11}, {"stress_22", s22}, {"stress_33", s33}, {"eqps_rate", rate}, {"tstar0", tstar},
                {"failure.d1", kD1}, {"failure.d2", kD2}, {"failure.d3", kD3}, {"failure.d4", kD4},
                {"failure.d5", kD5}, {"failure.reference_strain_rate", rate0}};
  return with_failure(v, "johnson_cook_damage");
}

}  // namespace

// JC damage (eq. 6.5) at constant triaxiality, rate and temperature: eps_f is the closed form
// [D1 + D2 exp(D3 sigma*)][1 + D4 ln(max(edot/edot0, 1))][1 + D5 T*], the damage after n steps is
// n Delta eps_p / eps_f (1e-12: a sum of n equal terms) and the point fails at the first step with
// n Delta eps_p >= eps_f, not before. The cases cover tension and compression triaxialities, a
// biaxial state and a rate below the reference (rate factor 1).
TEST(Failure, JohnsonCookDamageTriggersAtTheFailureStrain) {
  struct Case {
    double s11, s22, s33, triax, rate, rate0, tstar;
  };
  const Case cases[] = {
      {4e8, 0, 0, 1.0 / 3.0, 1e3, 1.0, 0.25},     // uniaxial tension
      {-4e8, 0, 0, -1.0 / 3.0, 1e3, 1.0, 0.25},   // uniaxial compression
      {4e8, 4e8, 0, 2.0 / 3.0, 2e3, 1.0, 0.0},    // equibiaxial tension
      {4e8, 0, 0, 1.0 / 3.0, 1e3, 1e5, 0.5},      // below the reference rate: factor 1
      {-1e8, 2e8, 5e8, 2.0 / (3.0 * std::sqrt(3.0)), 1e3, 1.0, 0.1},  // triaxial: tr 6e8, q sqrt(27e16)
  };
  const double dt = 1e-5;
  for (const Case& c : cases) {
    // sigma* from the principal stresses: q = sqrt(((s1-s2)^2 + (s2-s3)^2 + (s3-s1)^2)/2).
    const double tr = c.s11 + c.s22 + c.s33;
    const double q = std::sqrt(0.5 * ((c.s11 - c.s22) * (c.s11 - c.s22) + (c.s22 - c.s33) * (c.s22 - c.s33) +
                                      (c.s33 - c.s11) * (c.s33 - c.s11)));
    const double triax = tr / (3.0 * q);
    EXPECT_NEAR(triax, c.triax, 1e-15);
    const double ef = (kD1 + kD2 * std::exp(kD3 * triax)) * (1.0 + kD4 * std::log(std::max(c.rate / c.rate0, 1.0))) *
                      (1.0 + kD5 * c.tstar);
    const double de = c.rate * dt;
    const int n_fail = first_step_reaching(ef, de);
    SCOPED_TRACE("sigma* = " + std::to_string(triax) + ", eps_f = " + std::to_string(ef));
    PointDriver d("test_scripted_point", jc_values(c.s11, c.s22, c.s33, c.rate, c.rate0, c.tstar));
    run_scripted(d, n_fail + 3, dt, [&](int n, double damage, double failed) {
      if (n < n_fail) {
        ASSERT_EQ(failed, 0.0) << "step " << n;
        ASSERT_NEAR(damage, n * de / ef, 1e-12) << "step " << n;
      } else {
        ASSERT_EQ(failed, 1.0) << "step " << n;
        ASSERT_EQ(damage, 1.0);
      }
    });
  }
}

// Melt (eq. 6.6) with a scripted homologous temperature T* = rate t: fails at the first step with
// T* >= 1.
TEST(Failure, MeltTriggersAtTheMeltTemperatureScripted) {
  const double dt = 1e-6, rate = 1.0 / (0.7371 * 1000 * dt);  // T* = 1 after 737.1 steps
  ParamValues v = with_failure({{"tstar_rate", rate}}, "melt");
  PointDriver d("test_scripted_point", v);
  const int n_fail = first_step_reaching(1.0, rate * dt);
  EXPECT_EQ(n_fail, 738);
  run_scripted(d, n_fail + 2, dt, [&](int n, double damage, double failed) {
    ASSERT_EQ(failed, n >= n_fail ? 1.0 : 0.0) << "step " << n;
    if (n < n_fail) {
      ASSERT_NEAR(damage, n * rate * dt, 1e-12);  // damage = T* before melting
    }
  });
}

// Melt with a model that heats by its plastic work (thesis eq. 6.7): T = T0 + chi W_p/(rho c_p)
// and, for linear hardening, W_p(eps_p) = sigma_y0 eps_p + H eps_p^2/2 exactly. T* reaches 1 at the
// root eps_m of chi W_p(eps_m) = rho c_p (T_m - T0); the point fails on the first step whose eps_p
// is >= eps_m (so eps_p before that step is < eps_m). Isochoric proportional shear,
// F = diag(a, 1/a, 1).
TEST(Failure, MeltTriggersWhenPlasticHeatingReachesTheMeltTemperature) {
  const double rho = 7850, cp = 45, chi = 0.9, T0 = 300, Tm = 400, sy0 = 4e8, H = 1e9;
  ParamValues v{{"density", rho},          {"bulk_modulus", 160e9}, {"shear_modulus", 80e9},
                {"yield_stress", sy0},     {"hardening_modulus", H}, {"taylor_quinney", chi},
                {"specific_heat", cp},     {"reference_temperature", T0}, {"melt_temperature", Tm}};
  PointDriver d("test_heating_j2", with_failure(v, "melt"));
  const double W = rho * cp * (Tm - T0) / chi;
  const double eps_m = (-sy0 + std::sqrt(sy0 * sy0 + 2.0 * H * W)) / H;  // H/2 e^2 + sy0 e - W = 0
  ASSERT_GT(eps_m, 0.05);
  ASSERT_LT(eps_m, 0.15);
  const int N = 3000;
  const double dt = 1e-6, lna_max = 0.15;
  double eqps_prev = 0.0;
  int n_fail = 0;
  for (int n = 1; n <= N && n_fail == 0; ++n) {
    const double a = std::exp(lna_max * n / N);
    d.advance(Mat3::diag(a, 1.0 / a, 1.0), dt);
    const double eqps = d.state("eqps");
    if (d.state(kFailedField) == 1.0) {
      n_fail = n;
      EXPECT_GE(eqps, eps_m);
      EXPECT_LT(eqps_prev, eps_m);
      EXPECT_GE(d.state("temperature"), Tm - 1e-9);
    } else {
      EXPECT_LT(eqps, eps_m) << "step " << n;
      EXPECT_NEAR(d.state(kDamageField), (d.state("temperature") - T0) / (Tm - T0), 1e-12);
    }
    eqps_prev = eqps;
  }
  EXPECT_GT(n_fail, 0) << "never melted";
}

// TEPLA-F (eq. 6.8) with a fixed porosity f0 > 0 (isochoric J2 flow does not grow voids): fails at
// eps_p = eps_f sqrt(1 - (f0/fc)^2); damage is (f0/fc)^2 + (eps_p/eps_f)^2 before that.
TEST(Failure, TeplaTriggersOnTheFractureEllipse) {
  const double f0 = 0.1, fc = 0.3, epf = 0.5, rate = 1e3, dt = 1e-6;  // d eps_p = 1e-3 per step
  ParamValues v{{"eqps_rate", rate},
                {"failure.initial_porosity", f0},
                {"failure.critical_porosity", fc},
                {"failure.fracture_strain", epf}};
  PointDriver d("test_scripted_plastic", with_failure(v, "tepla"));
  const double eps_fail = epf * std::sqrt(1.0 - (f0 / fc) * (f0 / fc));  // 0.4714
  const int n_fail = first_step_reaching(eps_fail, rate * dt);
  EXPECT_EQ(n_fail, 472);
  run_scripted(d, n_fail + 2, dt, [&](int n, double damage, double failed) {
    const double e = n * rate * dt;
    if (n < n_fail) {
      ASSERT_EQ(failed, 0.0) << "step " << n;
      ASSERT_NEAR(damage, (f0 / fc) * (f0 / fc) + (e / epf) * (e / epf), 1e-12);
    } else {
      ASSERT_EQ(failed, 1.0) << "step " << n;
    }
  });
}

// TEPLA with Chu-Needleman strain-controlled nucleation: f(eps) = f0 + fN/2 [erf((eps - eN)/(sN
// sqrt2)) + erf(eN/(sN sqrt2))], the integral of the normal nucleation rate. The failure strain
// (root of (f/fc)^2 + (eps/epf)^2 = 1, by bisection here) is below the one without nucleation, and
// the point fails at the first step beyond it.
TEST(Failure, TeplaWithNucleationTriggersAtTheRootOfTheEllipse) {
  const double f0 = 0.02, fc = 0.2, epf = 0.6, fN = 0.1, eN = 0.3, sN = 0.1, rate = 1e3, dt = 1e-6;
  ParamValues v{{"eqps_rate", rate},           {"failure.initial_porosity", f0},  {"failure.critical_porosity", fc},
                {"failure.fracture_strain", epf}, {"failure.nucleation_porosity", fN}, {"failure.nucleation_strain", eN},
                {"failure.nucleation_stddev", sN}};
  auto f = [&](double e) {
    return f0 + 0.5 * fN * (std::erf((e - eN) / (sN * std::sqrt(2.0))) + std::erf(eN / (sN * std::sqrt(2.0))));
  };
  auto g = [&](double e) { return (f(e) / fc) * (f(e) / fc) + (e / epf) * (e / epf) - 1.0; };
  double lo = 0.0, hi = epf;
  for (int i = 0; i < 200; ++i) (g(0.5 * (lo + hi)) < 0.0 ? lo : hi) = 0.5 * (lo + hi);
  const double eps_fail = hi;
  EXPECT_LT(eps_fail, epf * std::sqrt(1.0 - (f0 / fc) * (f0 / fc)) - 0.05);  // nucleation matters
  // The trapezoidal integral of the nucleation rate reproduces f(eps) (independent check of the
  // closed form, 1e-6 with 1e5 intervals).
  double integral = f0;
  const int M = 100000;
  for (int i = 0; i < M; ++i) {
    auto rate_f = [&](double e) {
      return fN / (sN * std::sqrt(2.0 * 3.141592653589793)) * std::exp(-0.5 * ((e - eN) / sN) * ((e - eN) / sN));
    };
    const double e0 = eps_fail * i / M, e1 = eps_fail * (i + 1) / M;
    integral += 0.5 * (rate_f(e0) + rate_f(e1)) * (e1 - e0);
  }
  EXPECT_NEAR(integral, f(eps_fail), 1e-6);
  PointDriver d("test_scripted_plastic", with_failure(v, "tepla"));
  const int n_fail = first_step_reaching(eps_fail, rate * dt);
  run_scripted(d, n_fail + 2, dt, [&](int n, double, double failed) {
    ASSERT_EQ(failed, n >= n_fail ? 1.0 : 0.0) << "step " << n << " of expected " << n_fail;
  });
}

// Drucker stability (eq. 6.9) with a softening J2 model (H < 0) on an isochoric proportional path:
// there (sigma_{n+1} - sigma_n) : Delta eps^p = Delta q Delta eps_p, so the point fails exactly on
// the first plastic step on which the von Mises stress decreases. Never during elastic steps.
TEST(Failure, DruckerTriggersAtTheOnsetOfSoftening) {
  ParamValues v{{"density", 7850}, {"bulk_modulus", 160e9}, {"shear_modulus", 80e9}, {"yield_stress", 4e8},
                {"hardening_modulus", -2e9}};
  PointDriver d("test_heating_j2", with_failure(v, "drucker_stability"));
  const double dt = 1e-6;
  double q_prev = 0.0, eqps_prev = 0.0;
  int n_expected = 0, n_fail = 0, n_plastic = 0;
  for (int n = 1; n <= 400 && n_fail == 0; ++n) {
    const double a = std::exp(2e-5 * n);
    d.advance(Mat3::diag(a, 1.0 / a, 1.0), dt);
    const double q = von_mises(d.stress()), eqps = d.state("eqps");
    if (eqps > eqps_prev && n_plastic == 0) n_plastic = n;
    if (eqps > eqps_prev && q < q_prev && n_expected == 0) n_expected = n;
    if (d.state(kFailedField) == 1.0) n_fail = n;
    q_prev = q;
    eqps_prev = eqps;
  }
  ASSERT_GT(n_plastic, 1);  // some elastic steps first
  EXPECT_GT(n_expected, 0);
  EXPECT_EQ(n_fail, n_expected);
  EXPECT_LE(n_fail, n_plastic + 1);  // at the latest the second plastic step
}

// With hardening H >= 0 Drucker's postulate holds: no failure over long plastic paths, proportional
// (isochoric stretch) and non-proportional (a stretch whose direction turns), including perfect
// plasticity H = 0, where on the proportional path the product is 0 up to round-off and the
// tolerance (failure.hpp, drucker_tolerance) must absorb it.
TEST(Failure, DruckerNeverTriggersWithHardeningOrPerfectPlasticity) {
  for (double H : {0.0, 1e9}) {
    for (bool turning : {false, true}) {
      ParamValues v{{"density", 7850}, {"bulk_modulus", 160e9}, {"shear_modulus", 80e9}, {"yield_stress", 4e8},
                    {"hardening_modulus", H}};
      PointDriver d("test_heating_j2", with_failure(v, "drucker_stability"));
      const int N = 3000;
      const double dt = 1e-6;
      Mat3 F = Mat3::identity();
      for (int n = 1; n <= N; ++n) {
        const double phi = turning ? 3.0 * n / N : 0.0;  // direction turns by 3 rad in the 1-2 plane
        const Mat3 Q = rotation_about(Vec3{{0, 0, 1}}, phi);
        const Mat3 step = Mat3::identity() + 1e-4 * rotate(Q, Mat3::diag(1.0, -1.0, 0.0));
        F = step * F;
        d.advance(F, dt);
        ASSERT_EQ(d.state(kFailedField), 0.0) << "H = " << H << (turning ? ", turning" : "") << ", step " << n;
      }
      EXPECT_GT(d.state("eqps"), 0.2);  // the path was plastic
    }
  }
}

// Max stress (eq. 6.10) with linear_elastic (no plasticity needed) in uniaxial strain: the von
// Mises stress is |sigma11 - sigma22| = 2G |S_n|, S_n = sum of the midpoint increments
// 2 (F_{k+1}/F_k - 1)/(F_{k+1}/F_k + 1) (stretch_increment, material_driver.hpp; the hypoelastic
// update of test_linear_elastic.cpp), so the point fails at the first n with 2G |S_n| > sigma_max;
// damage before is 2G |S_n| / sigma_max (1e-9: the stress is computed with round-off of 1e-12
// relative). Failure is permanent: unloading afterwards keeps failed = 1.
TEST(Failure, MaxStressTriggersAtTheAnalyticStep) {
  const double K = 160e9, G = 79e9, smax = 3.0e8 + 1234.5;
  PointDriver d("linear_elastic", with_failure({{"density", 7850}, {"bulk_modulus", K}, {"shear_modulus", G},
                                                {"failure.max_stress", smax}},
                                               "max_stress"));
  const double dt = 1e-7, de = -1e-5;
  double S = 0.0, F_prev = 1.0;
  int n_expected = 0;
  for (int n = 1; n <= 400; ++n) {
    const double Fn = 1.0 + de * n;
    S += stretch_increment(Fn, F_prev);
    F_prev = Fn;
    const double q = 2.0 * G * std::abs(S);
    if (q > smax && n_expected == 0) {
      n_expected = n;
      ASSERT_GT((q - smax) / smax, 1e-6);  // not within round-off of the threshold
    }
    d.advance(Mat3::diag(Fn, 1.0, 1.0), dt);
    EXPECT_NEAR(von_mises(d.stress()), q, 1e-9 * q);
    if (n_expected == 0 || n < n_expected) {
      ASSERT_EQ(d.state(kFailedField), 0.0) << n;
      ASSERT_NEAR(d.state(kDamageField), q / smax, 1e-9);
    } else {
      ASSERT_EQ(d.state(kFailedField), 1.0) << n;
      ASSERT_EQ(d.state(kDamageField), 1.0);
    }
  }
  ASSERT_GT(n_expected, 100);
  // Unload to F = 1: the stress vanishes but the point stays failed.
  for (int n = 1; n <= 10; ++n) d.advance(Mat3::diag(F_prev + (1.0 - F_prev) * n / 10, 1.0, 1.0), dt);
  EXPECT_LT(von_mises(d.stress()), 1e-3 * smax);
  EXPECT_EQ(d.state(kFailedField), 1.0);
  EXPECT_EQ(d.state(kDamageField), 1.0);
}

// A criterion adds the state fields damage and failed to this material instance only.
TEST(Failure, StateFieldsOnlyWithACriterion) {
  const ParamValues le{{"density", 7850}, {"bulk_modulus", 160e9}, {"shear_modulus", 79e9}};
  EXPECT_TRUE(make_material("linear_elastic", le)->state_fields().empty());
  ParamValues le_max = le;
  le_max["failure.max_stress"] = 1e9;
  const auto m2 = make_material("linear_elastic", with_failure(le_max, "max_stress"));
  const auto f = m2->state_fields();
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f[0].name, "damage");
  EXPECT_EQ(f[1].name, "failed");
  // Model state first, then failure's.
  ParamValues j2{{"density", 7850}, {"bulk_modulus", 160e9}, {"shear_modulus", 79e9}, {"yield_stress", 4e8},
                 {"failure.critical_porosity", 0.3}, {"failure.fracture_strain", 0.5}};
  const auto h = make_material("test_heating_j2", with_failure(j2, "tepla"));
  const auto hf = h->state_fields();
  ASSERT_EQ(hf.size(), 4u);
  EXPECT_EQ(hf[0].name, "eqps");
  EXPECT_EQ(hf[2].name, "damage");
  EXPECT_EQ(hf[3].name, "failed");
}

// Every registered model lists the failure.* parameters (ballista info shows them).
TEST(Failure, EveryModelHasTheFailureParameters) {
  for (const MaterialFactory& f : material_registry()) {
    int n = 0;
    for (const ParamSpec& s : f.params) n += s.name.rfind("failure.", 0) == 0;
    EXPECT_EQ(n, static_cast<int>(failure_param_specs().size())) << f.model;
  }
}

// ParamError names the key the deck layer points at.
TEST(Failure, ImpossibleCombinationsAreRejectedWhenMade) {
  auto param_of = [](const std::string& model, const ParamValues& v) -> std::string {
    try {
      make_material(model, v);
    } catch (const ParamError& e) {
      return e.param() + ": " + e.what();
    }
    return "accepted";
  };
  const ParamValues le{{"density", 7850}, {"bulk_modulus", 160e9}, {"shear_modulus", 79e9}};
  auto starts = [](const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; };
  // Criteria that need plastic strain or temperature, on a model without them.
  for (const char* c : {"johnson_cook_damage", "tepla", "drucker_stability"}) {
    const std::string r = param_of("linear_elastic", with_failure(le, c));
    EXPECT_TRUE(starts(r, "failure.criterion: ")) << r;
    EXPECT_NE(r.find("plastic strain"), std::string::npos) << r;
  }
  const std::string melt = param_of("test_scripted_plastic", with_failure({}, "melt"));
  EXPECT_TRUE(starts(melt, "failure.criterion: ")) << melt;
  EXPECT_NE(melt.find("temperature"), std::string::npos) << melt;
  EXPECT_EQ(param_of("test_scripted_point", with_failure({}, "melt")), "accepted");
  // Missing constants name themselves.
  ParamValues jc = jc_values(1, 0, 0, 1, 1, 0);
  jc.erase("failure.d3");
  EXPECT_TRUE(starts(param_of("test_scripted_point", jc), "failure.d3: ")) << param_of("test_scripted_point", jc);
  jc = jc_values(1, 0, 0, 1, 1, 0);
  jc["failure.d1"] = std::numeric_limits<double>::quiet_NaN();  // as the deck leaves an absent optional
  EXPECT_TRUE(starts(param_of("test_scripted_point", jc), "failure.d1: failure.d1 is required"));
  // D5 != 0 needs temperature; D5 = 0 does not.
  jc = jc_values(1, 0, 0, 1, 1, 0);
  EXPECT_TRUE(starts(param_of("test_scripted_plastic", jc), "failure.d5: "));
  jc["failure.d5"] = 0.0;
  EXPECT_EQ(param_of("test_scripted_plastic", jc), "accepted");
  EXPECT_TRUE(starts(param_of("linear_elastic", with_failure(le, "max_stress")), "failure.max_stress: "));
  ParamValues tp{{"failure.critical_porosity", 0.2}, {"failure.fracture_strain", 0.5}, {"failure.initial_porosity", 0.2}};
  EXPECT_TRUE(starts(param_of("test_scripted_plastic", with_failure(tp, "tepla")), "failure.initial_porosity: "));
  tp.erase("failure.fracture_strain");
  tp["failure.initial_porosity"] = 0.0;
  EXPECT_TRUE(starts(param_of("test_scripted_plastic", with_failure(tp, "tepla")), "failure.fracture_strain: "));
  // Unknown words, and an erosion without a criterion.
  EXPECT_TRUE(starts(param_of("linear_elastic", with_failure(le, "spall")), "failure.criterion: unknown"));
  EXPECT_TRUE(starts(param_of("linear_elastic", with_failure(le, "none", "delete")), "failure.erosion: unknown"));
  EXPECT_TRUE(starts(param_of("linear_elastic", with_failure(le, "none", "zero_stress")), "failure.erosion: "));
}

// The failure strain helper is the closed form (spot values computed by hand): sigma* = 0,
// edot* = e (ln = 1), T* = 0.5 with D = (0.1, 0.2, 3, 0.05, 2): (0.1 + 0.2)(1.05)(2) = 0.63.
TEST(Failure, JohnsonCookFailureStrainClosedForm) {
  FailureModel m;
  m.d1 = 0.1, m.d2 = 0.2, m.d3 = 3.0, m.d4 = 0.05, m.d5 = 2.0, m.reference_rate = 10.0;
  EXPECT_NEAR(jc_failure_strain(m, 0.0, 10.0 * std::exp(1.0), 0.5), 0.63, 1e-15);
  EXPECT_NEAR(jc_failure_strain(m, 1.0, 1.0, 0.0), 0.1 + 0.2 * std::exp(3.0), 1e-14);  // rate < edot0
}

}  // namespace test_failure
