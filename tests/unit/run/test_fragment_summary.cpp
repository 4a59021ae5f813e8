// summary.json "fragments" (run/fragment_summary.hpp) from a synthetic fragments table: the last
// snapshot only, counts and masses exact, the Mott fit as analysis/mott_fit.hpp gives it, absent values
// and a reason below three fragments; the hook reacts to the table name only; the plot launcher
// reports a folder without fragments.csv (tools/plot_fragments.py exit status 2). The figures
// themselves are checked by tests/plots/check_fragment_plots.py.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "analysis/mott_fit.hpp"
#include "run/fragment_plots.hpp"
#include "run/fragment_summary.hpp"
#include "support/test_files.hpp"

namespace test_fragment_summary {

using namespace ballista;

namespace {

ResultTable table(const std::vector<std::pair<double, double>>& time_mass) {
  ResultTable t{"fragments", {"time", "fragment", "points", "mass"}, {}};
  for (const auto& [time, mass] : time_mass) t.rows.push_back({time, 0.0, 1.0, mass});
  return t;
}

}  // namespace

TEST(FragmentSummary, StatisticsAboveAMinimumMassLeaveOutTheDust) {
  // Last snapshot: three fragments of 9, 4 and 1 g and 100 loose points of 5 mg. Above 0.1 g only
  // the three count: their mean 14/3 g and the Mott fit of exactly those masses; the statistics of
  // all 103 are unchanged beside them. (1, 4, 9 g: sqrt(mu) = (1 + 2 + 3)/3 sqrt(g), mu = 4 g.)
  std::vector<std::pair<double, double>> rows = {{1e-6, 20e-3}, {2e-6, 9e-3}, {2e-6, 4e-3}, {2e-6, 1e-3}};
  for (int k = 0; k < 100; ++k) rows.push_back({2e-6, 5e-6});
  const ResultTable t = table(rows);
  const JsonValue all = fragment_summary(t);
  const JsonValue j = fragment_summary(t, 0.1e-3);
  EXPECT_FALSE(all.contains("above_min_mass"));  // without a minimum, the summary as before
  EXPECT_EQ(j.at("count").as_int(), 103);
  EXPECT_EQ(j.at("mott_mu").as_number(), all.at("mott_mu").as_number());
  const JsonValue& a = j.at("above_min_mass");
  EXPECT_EQ(a.at("min_mass").as_number(), 0.1e-3);
  EXPECT_EQ(a.at("count").as_int(), 3);
  EXPECT_EQ(a.at("largest_mass").as_number(), 9e-3);
  EXPECT_NEAR(a.at("mean_mass").as_number(), 14e-3 / 3.0, 1e-15);
  EXPECT_NEAR(a.at("mott_mu").as_number(), 4e-3, 1e-15);  // to round-off (MottFit.ThreeFragmentsByHand)
  EXPECT_EQ(a.at("mott_N0").as_number(), 3.0);
  // All 103: the dust sets the Mott scale near a point's mass.
  EXPECT_LT(all.at("mott_mu").as_number(), 0.1e-3);
  // A minimum above every fragment: none counted, no fit, a reason.
  const JsonValue none = fragment_summary(t, 1.0).at("above_min_mass");
  EXPECT_EQ(none.at("count").as_int(), 0);
  EXPECT_TRUE(none.contains("mott_reason"));
}

TEST(FragmentSummary, LastSnapshotAndMottFit) {
  // Snapshot 1 us: one body; 2 us: four fragments of 4, 3, 2, 1 g (sorted by mass, as written).
  const ResultTable t = table({{1e-6, 10e-3}, {2e-6, 4e-3}, {2e-6, 3e-3}, {2e-6, 2e-3}, {2e-6, 1e-3}});
  const JsonValue j = fragment_summary(t);
  EXPECT_EQ(j.at("time").as_number(), 2e-6);
  EXPECT_EQ(j.at("count").as_int(), 4);
  EXPECT_EQ(j.at("largest_mass").as_number(), 4e-3);
  EXPECT_NEAR(j.at("total_mass").as_number(), 10e-3, 1e-15 * 10e-3);  // a sum: rounding
  EXPECT_NEAR(j.at("mean_mass").as_number(), 2.5e-3, 1e-15 * 2.5e-3);
  // (16 + 9 + 4 + 1) / 10 g: the fragment the average gram is in.
  EXPECT_NEAR(j.at("mass_weighted_mean_mass").as_number(), 3e-3, 1e-15 * 3e-3);
  const MottFit f = fit_mott({4e-3, 3e-3, 2e-3, 1e-3});
  ASSERT_TRUE(f.ok);
  EXPECT_EQ(j.at("mott_N0").as_number(), 4.0);
  EXPECT_EQ(j.at("mott_mu").as_number(), f.mu);
  EXPECT_EQ(j.at("mott_r2").as_number(), f.r2);
  EXPECT_FALSE(j.contains("mott_reason"));
}

TEST(FragmentSummary, TooFewFragmentsLeaveTheFitOutWithAReason) {
  const JsonValue j = fragment_summary(table({{0.0, 1e-3}, {0.0, 2e-3}}));
  EXPECT_EQ(j.at("count").as_int(), 2);
  EXPECT_EQ(j.at("largest_mass").as_number(), 2e-3);
  EXPECT_FALSE(j.contains("mott_N0"));
  EXPECT_FALSE(j.contains("mott_mu"));
  EXPECT_FALSE(j.contains("mott_r2"));
  EXPECT_NE(j.at("mott_reason").as_string().find("at least 3"), std::string::npos);
  const JsonValue none = fragment_summary(table({}));
  EXPECT_EQ(none.at("count").as_int(), 0);
  EXPECT_FALSE(none.contains("mean_mass"));
  EXPECT_FALSE(none.contains("mass_weighted_mean_mass"));
  EXPECT_TRUE(non_finite_numbers(none).empty());
  // Equal masses: a fit (mu = the mass) but no Mott-plot line: r2 left out rather than NaN.
  const JsonValue equal = fragment_summary(table({{0.0, 1e-3}, {0.0, 1e-3}, {0.0, 1e-3}}));
  EXPECT_NEAR(equal.at("mott_mu").as_number(), 1e-3, 1e-18);
  EXPECT_FALSE(equal.contains("mott_r2"));
  EXPECT_TRUE(non_finite_numbers(equal).empty());
}

TEST(FragmentSummary, HookReactsToTheTableNameOnly) {
  test::TempDir dir("frag_summary");
  JsonValue summary = JsonValue::object();
  ResultTable other = table({{0.0, 1e-3}, {0.0, 2e-3}, {0.0, 3e-3}});
  other.name = "clusters";
  report_fragments({other}, dir.path.string(), false, summary);
  EXPECT_FALSE(summary.contains("fragments"));
  report_fragments({other, table({{0.0, 1e-3}, {0.0, 2e-3}, {0.0, 3e-3}})}, dir.path.string(), false, summary);
  ASSERT_TRUE(summary.contains("fragments"));
  EXPECT_EQ(summary.at("fragments").at("count").as_int(), 3);
  // A table without masses is a warning, not an exception out of the run loop.
  JsonValue s2 = JsonValue::object();
  report_fragments({ResultTable{"fragments", {"time", "speed"}, {{0.0, 1.0}}}}, dir.path.string(), false, s2);
  EXPECT_FALSE(s2.contains("fragments"));
}

TEST(FragmentPlots, FolderWithoutFragmentsIsAnError) {
  test::TempDir dir("frag_plots");
  const std::string err = make_fragment_plots(dir.path.string());
  EXPECT_NE(err.find("plot_fragments.py"), std::string::npos) << err;
  EXPECT_NE(err.find("failed with status 2"), std::string::npos) << err;
}

}  // namespace test_fragment_summary
