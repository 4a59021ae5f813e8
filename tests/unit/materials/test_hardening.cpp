// Isotropic hardening laws (src/materials/hardening.hpp): value against the published forms,
// slope against central differences, the plastic-work integral against Gauss-Legendre
// quadrature, and the parameter checks of make_hardening.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "materials/hardening.hpp"

namespace test_hardening {

using namespace ballista;

namespace {

IsotropicHardening law(HardeningLaw l) {
  IsotropicHardening h;
  h.law = l;
  h.yield0 = 300e6;
  if (l != HardeningLaw::PowerLaw) h.modulus = 1.5e9;
  h.coefficient = 450e6;
  h.exponent = 0.35;
  h.saturation = 220e6;
  h.rate = 17.0;
  return h;
}

/// Composite 5-point Gauss-Legendre quadrature (Abramowitz & Stegun 25.4.30 nodes/weights) of the
/// flow stress over [a, a + d] with 400 panels, nodes placed as a + d t so that a tiny d on a large
/// a keeps its digits; exact to ~1e-15 for these smooth integrands away from e = 0 (the power law
/// is integrated from a > 0 here).
double quad(const IsotropicHardening& h, double a, double d) {
  const double x[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
  const double w[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891,
                       0.2369268850561891};
  const int n = 400;
  double s = 0.0;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < 5; ++i) s += w[i] * h.value(a + d * (k + 0.5 + 0.5 * x[i]) / n);
  return 0.5 * d / n * s;
}

}  // namespace

// value(): the three laws of the header, written out here from their sources.
TEST(Hardening, ValuesMatchPublishedForms) {
  for (double e : {0.0, 1e-6, 0.01, 0.2, 1.5}) {
    EXPECT_DOUBLE_EQ(law(HardeningLaw::Linear).value(e), 300e6 + 1.5e9 * e);
    EXPECT_DOUBLE_EQ(law(HardeningLaw::PowerLaw).value(e), 300e6 + 450e6 * std::pow(e, 0.35));          // Ludwik
    EXPECT_NEAR(law(HardeningLaw::Voce).value(e), 300e6 + 1.5e9 * e + 220e6 * (1 - std::exp(-17 * e)),  // Voce
                1e-7);
  }
  // Voce saturates: sigma_y - H e -> sigma_y0 + Q.
  EXPECT_NEAR(law(HardeningLaw::Voce).value(10.0) - 1.5e9 * 10.0, 520e6, 1e-6);
}

// slope() against central differences (h = 1e-7 e: truncation ~(h/e)^2 ~ 1e-14, round-off
// ~1e-16 sigma/(h slope) ~ 1e-7 at worst; 1e-6 relative asserted). Power law: infinite at e = 0
// for n < 1, zero for n > 1.
TEST(Hardening, SlopeMatchesFiniteDifferences) {
  for (HardeningLaw l : {HardeningLaw::Linear, HardeningLaw::PowerLaw, HardeningLaw::Voce}) {
    const IsotropicHardening h = law(l);
    for (double e : {1e-4, 0.01, 0.2, 1.5}) {
      const double d = 1e-7 * e;
      const double fd = (h.value(e + d) - h.value(e - d)) / (2 * d);
      EXPECT_NEAR(h.slope(e), fd, 1e-6 * std::abs(h.slope(e))) << static_cast<int>(l) << " e = " << e;
    }
  }
  EXPECT_EQ(law(HardeningLaw::PowerLaw).slope(0.0), std::numeric_limits<double>::infinity());
  IsotropicHardening h = law(HardeningLaw::PowerLaw);
  h.exponent = 2.0;
  EXPECT_EQ(h.slope(0.0), 0.0);
  h.coefficient = 0.0;
  h.exponent = 0.5;
  EXPECT_EQ(h.slope(0.0), 0.0);  // no 0 * inf = NaN for a vanishing coefficient
}

// integral(e0, de) = int_{e0}^{e0+de} sigma_y against quadrature (1e-13 relative), including a
// tiny increment on a large e0 (where a difference of antiderivatives would lose ~8 digits) and
// the power law from e0 = 0 (closed form sigma_y0 de + k de^(n+1)/(n+1)).
TEST(Hardening, IntegralIsExact) {
  for (HardeningLaw l : {HardeningLaw::Linear, HardeningLaw::PowerLaw, HardeningLaw::Voce}) {
    const IsotropicHardening h = law(l);
    for (auto [e0, de] : {std::pair{0.01, 0.05}, {0.3, 1e-3}, {1.2, 1e-9}, {0.05, 0.8}}) {
      const double q = quad(h, e0, de);
      EXPECT_NEAR(h.integral(e0, de), q, 1e-13 * q) << static_cast<int>(l) << " " << e0 << " " << de;
    }
  }
  const IsotropicHardening p = law(HardeningLaw::PowerLaw);
  EXPECT_NEAR(p.integral(0.0, 0.02), 300e6 * 0.02 + 450e6 * std::pow(0.02, 1.35) / 1.35, 1e-6);
  // Additivity: integral over [a, c] = [a, b] + [b, c] (what makes the per-step sums exact).
  for (HardeningLaw l : {HardeningLaw::Linear, HardeningLaw::PowerLaw, HardeningLaw::Voce}) {
    const IsotropicHardening h = law(l);
    EXPECT_NEAR(h.integral(0.0, 0.3), h.integral(0.0, 0.1) + h.integral(0.1, 0.2), 1e-14 * h.integral(0.0, 0.3));
  }
}

// make_hardening: defaults, required keys per law, keys of other laws rejected by name.
TEST(Hardening, MakeFromParameters) {
  ParamValues v{{"yield_stress", 250e6}};
  IsotropicHardening h = make_hardening(v);
  EXPECT_EQ(h.law, HardeningLaw::Linear);
  EXPECT_EQ(h.modulus, 0.0);
  EXPECT_EQ(h.value(0.5), 250e6);
  v["hardening_modulus"] = 1e9;
  EXPECT_EQ(make_hardening(v).value(0.5), 250e6 + 0.5e9);
  auto key = [](const ParamValues& x) -> std::string {
    try {
      make_hardening(x);
    } catch (const ParamError& e) {
      return e.param();
    }
    return "";
  };
  EXPECT_EQ(key({{"hardening_modulus", 1e9}}), "yield_stress");
  EXPECT_EQ(key({{"yield_stress", 0.0}}), "yield_stress");
  ParamValues p{{"yield_stress", 250e6}, {"hardening_coefficient", 1e8}, {"hardening_exponent", 0.4}};
  EXPECT_EQ(key(p), "hardening_coefficient");  // linear law does not use it
  p.choices["hardening_law"] = "power_law";
  EXPECT_EQ(key(p), "");
  EXPECT_EQ(make_hardening(p).law, HardeningLaw::PowerLaw);
  p["hardening_exponent"] = 0.0;
  EXPECT_EQ(key(p), "hardening_exponent");
  p["hardening_exponent"] = std::numeric_limits<double>::quiet_NaN();  // absent, as the deck fills it
  EXPECT_EQ(key(p), "hardening_exponent");
  ParamValues q{{"yield_stress", 250e6}, {"saturation_stress", 1e8}, {"saturation_rate", 0.0}};
  q.choices["hardening_law"] = "voce";
  EXPECT_EQ(key(q), "saturation_rate");
  q["saturation_rate"] = 5.0;
  EXPECT_EQ(key(q), "");
  q.choices["hardening_law"] = "exponential";
  EXPECT_EQ(key(q), "hardening_law");
  // Spec list: names, units, the enumerated law with its default.
  const auto specs = hardening_param_specs();
  ASSERT_EQ(specs.size(), 5u);
  EXPECT_EQ(specs[0].name, "hardening_law");
  EXPECT_EQ(specs[0].default_choice, "linear");
  EXPECT_EQ(specs[1].unit, "Pa");
  EXPECT_EQ(specs[2].unit, "1");
}

}  // namespace test_hardening
