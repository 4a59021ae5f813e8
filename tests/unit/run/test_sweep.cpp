// `ballista sweep` pieces that do not run a solver: --vary parsing (errors name the option),
// the Cartesian product, the flattening of summary.json, the table (union of columns, failed
// runs, CSV quoting, JSON kinds) and the plan (threads per run, up-front deck validation).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "core/error.hpp"
#include "run/sweep.hpp"
#include "run/sweep_table.hpp"
#include "support/test_files.hpp"

namespace test_sweep {

using namespace ballista;

namespace {

std::string error_of(const std::vector<std::string>& vary) {
  try {
    parse_vary_options(vary);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const std::string kDeck = std::string(BALLISTA_SOURCE_DIR) + "/examples/elastic_disks.yaml";

}  // namespace

TEST(SweepVary, SplitsValuesOutsideBracketsAndQuotes) {
  const SweepAxis a = parse_vary(" bodies.0.velocity = [0,-100,0], [0,-200,0] ,{a: 1, b: 2},'x,y'");
  EXPECT_EQ(a.key, "bodies.0.velocity");
  EXPECT_EQ(a.values, (std::vector<std::string>{"[0,-100,0]", "[0,-200,0]", "{a: 1, b: 2}", "'x,y'"}));
  EXPECT_EQ(parse_vary("materials.cu.yield_stress=4e8").values, std::vector<std::string>{"4e8"});
}

TEST(SweepVary, MalformedOptionsNameTheOption) {
  EXPECT_NE(error_of({"simulation.cfl"}).find("--vary 'simulation.cfl': no '='"), std::string::npos);
  EXPECT_NE(error_of({"=1,2"}).find("empty key path"), std::string::npos);
  EXPECT_NE(error_of({"a..b=1"}).find("empty component"), std::string::npos);
  EXPECT_NE(error_of({"simulation.cfl= "}).find("--vary 'simulation.cfl= ': empty value list"), std::string::npos);
  EXPECT_NE(error_of({"simulation.cfl=0.1,,0.2"}).find("empty value (value 2)"), std::string::npos);
  EXPECT_NE(error_of({"simulation.cfl=0.1,"}).find("empty value (value 2)"), std::string::npos);
  EXPECT_NE(error_of({"v=[1,2"}).find("unbalanced"), std::string::npos);
  EXPECT_NE(error_of({"v=1]"}).find("unbalanced ']'"), std::string::npos);
  EXPECT_NE(error_of({"v='a"}).find("unterminated quote"), std::string::npos);
  EXPECT_NE(error_of({"a=1", "a=2,3"}).find("key 'a' is varied twice"), std::string::npos);
  EXPECT_EQ(error_of({"a=1", "b=2,3"}), "");
}

TEST(SweepProduct, CartesianProductLastAxisFastest) {
  const std::vector<SweepAxis> axes{{"a", {"1", "2"}}, {"b", {"x", "y", "z"}}};
  const auto runs = sweep_product(axes);
  ASSERT_EQ(runs.size(), 6u);  // 2 x 3
  const std::vector<std::vector<std::string>> expected{{"1", "x"}, {"1", "y"}, {"1", "z"},
                                                       {"2", "x"}, {"2", "y"}, {"2", "z"}};
  EXPECT_EQ(runs, expected);
  EXPECT_EQ(sweep_product({}).size(), 1u);  // no axis: the deck itself, once
  EXPECT_EQ(sweep_product({{"a", {"1"}}, {"b", {"2"}}, {"c", {"3", "4"}}}).size(), 2u);
}

TEST(SweepTable, FlattensSummaryKeepingKinds) {
  const YAML::Node s = YAML::Load(
      R"({"status": "completed", "deck": "d.yaml", "tracked_particles": [3, 7], "probes": {"max_eqps": 0.25},
          "statistics": {"steps": 12, "solver": "mpm", "ok": true, "min_dt": null, "label": "42"}})");
  const auto f = flatten_summary(s, {"status"});
  std::vector<std::string> names;
  for (const auto& [n, c] : f) names.push_back(n);
  EXPECT_EQ(names, (std::vector<std::string>{"deck", "tracked_particles.0", "tracked_particles.1", "probes.max_eqps",
                                             "statistics.steps", "statistics.solver", "statistics.ok",
                                             "statistics.label"}));  // null min_dt: no cell
  EXPECT_EQ(f[3].second.kind, SweepCell::Kind::Number);
  EXPECT_EQ(f[3].second.text, "0.25");
  EXPECT_EQ(f[5].second.kind, SweepCell::Kind::String);
  EXPECT_EQ(f[6].second.kind, SweepCell::Kind::Bool);
  EXPECT_EQ(f[7].second.kind, SweepCell::Kind::String);  // a quoted "42" stays a string
  EXPECT_EQ(sweep_cell("1e-3").kind, SweepCell::Kind::Number);
  EXPECT_EQ(sweep_cell("[1,2]").kind, SweepCell::Kind::String);
  EXPECT_EQ(sweep_cell("nan").kind, SweepCell::Kind::String);  // JSON has no NaN
}

TEST(SweepTable, UnionOfColumnsAndFailedRuns) {
  SweepTable t({{"bodies.0.velocity", {"[0,1,0]", "[0,2,0]"}}, {"materials.m.density", {"7800"}}});
  t.add({0,
         {"[0,1,0]", "7800"},
         "completed",
         "",
         {{"probes.a", sweep_cell("1.5")}, {"statistics.steps", sweep_cell("10")}}});
  t.add({1,
         {"[0,2,0]", "7800"},
         "failed",
         "particle 3 left the grid, at \"x\"\n  position [1, 2]",
         {{"probes.a", sweep_cell("2.5")}, {"failed_step", sweep_cell("7")}}});
  EXPECT_EQ(t.failed(), 1);
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"run", "bodies.0.velocity", "materials.m.density", "status", "error",
                                                   "probes.a", "statistics.steps", "failed_step"}));
  const std::string expected =
      "run,bodies.0.velocity,materials.m.density,status,error,probes.a,statistics.steps,failed_"
      "step\n"
      "0,\"[0,1,0]\",7800,completed,,1.5,10,\n"
      "1,\"[0,2,0]\",7800,failed,\"particle 3 left the grid, at \"\"x\"\"\n  position [1, "
      "2]\",2.5,,7\n";
  EXPECT_EQ(t.csv(), expected);

  // JSON: the same rows, numbers as numbers, missing cells and empty errors as null.
  const YAML::Node j = YAML::Load(t.json().dump(2));
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["axes"][0]["key"].as<std::string>(), "bodies.0.velocity");
  EXPECT_EQ(j["columns"].size(), 8u);
  EXPECT_EQ(j["runs"][0]["materials.m.density"].as<double>(), 7800.0);
  EXPECT_EQ(j["runs"][0]["bodies.0.velocity"].as<std::string>(), "[0,1,0]");
  EXPECT_TRUE(j["runs"][0]["error"].IsNull());
  EXPECT_TRUE(j["runs"][0]["failed_step"].IsNull());
  EXPECT_TRUE(j["runs"][1]["statistics.steps"].IsNull());
  EXPECT_EQ(j["runs"][1]["status"].as<std::string>(), "failed");
  EXPECT_EQ(j["runs"][1]["failed_step"].as<int>(), 7);

  test::TempDir dir;
  t.write(dir.path);
  EXPECT_EQ(test::slurp(dir.path / "sweep.csv"), expected);
  EXPECT_EQ(YAML::LoadFile((dir.path / "sweep.json").string())["runs"].size(), 2u);
  EXPECT_EQ(test::count_tmp(dir.path), 0);
}

TEST(SweepPlan, ThreadsPerRunAndOverrideOrder) {
  EXPECT_EQ(sweep_threads_per_run(8, 3), 2);
  EXPECT_EQ(sweep_threads_per_run(2, 4), 1);  // never 0
  SweepOptions o;
  o.deck = kDeck;
  o.vary = {"simulation.cfl=0.1,0.2", "materials.soft.youngs_modulus=1000,2000"};
  o.set = {"grid.cell_size=0.1"};
  o.out_dir = "sweep_out";
  o.jobs = 2;
  o.cores = 6;
  const SweepPlan p = plan_sweep(o);
  ASSERT_EQ(p.runs.size(), 4u);
  EXPECT_EQ(p.threads_per_run, 3);
  EXPECT_EQ(p.runs[1].dir, std::filesystem::path("sweep_out/run_1"));
  EXPECT_EQ(p.runs[1].overrides,
            (std::vector<std::string>{"simulation.threads=3", "grid.cell_size=0.1", "simulation.cfl=0.1",
                                      "materials.soft.youngs_modulus=2000"}));
  o.set.push_back("simulation.threads=1");  // the user's choice is left alone
  EXPECT_EQ(plan_sweep(o).threads_per_run, 0);
  o.set.pop_back();
  o.jobs = 1;  // one run at a time: the deck's threads
  EXPECT_EQ(plan_sweep(o).threads_per_run, 0);
}

TEST(SweepPlan, BadDeckOfAnyCombinationStopsBeforeRunning) {
  SweepOptions o;
  o.deck = kDeck;
  o.out_dir = "never_created";
  o.vary = {"simulation.cfl=0.1,7"};  // the second run's value is out of range
  try {
    plan_sweep(o);
    FAIL() << "expected a SweepDeckError";
  } catch (const SweepDeckError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("run 1 (simulation.cfl=7)"), std::string::npos) << m;
    EXPECT_NE(m.find("'simulation.cfl'"), std::string::npos) << m;
    EXPECT_NE(m.find("elastic_disks.yaml"), std::string::npos) << m;
  }
  o.vary = {"simulation.cfll=0.1"};  // unknown key: the deck reader's suggestion comes through
  try {
    plan_sweep(o);
    FAIL() << "expected a SweepDeckError";
  } catch (const SweepDeckError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'cfl'"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists("never_created"));
  o.vary = {};
  EXPECT_THROW(plan_sweep(o), Error);  // nothing to vary
  o.vary = {"simulation.cfl=0.1"};
  o.jobs = 0;
  EXPECT_THROW(plan_sweep(o), Error);
}

TEST(SweepRun, FailedChildrenAreRecordedAndPostStepsSeeTheTable) {
  // /bin/sh given "run DECK ..." cannot open a script named "run": every run exits non-zero without
  // a summary.json, so each row must say failed with the exit status and the end of its log.
  test::TempDir dir;
  SweepOptions o;
  o.deck = kDeck;
  o.vary = {"simulation.cfl=0.1,0.2,0.3"};
  o.out_dir = dir.path / "s";
  o.jobs = 2;
  o.quiet = true;
  o.executable = "/bin/sh";
  int post_calls = 0;
  o.post_steps.push_back([&](const SweepTable& t, const std::filesystem::path& out) {
    ++post_calls;
    EXPECT_EQ(t.rows().size(), 3u);
    EXPECT_TRUE(std::filesystem::exists(out / "sweep.csv"));  // the table is written before post steps
  });
  const SweepTable t = run_sweep(o);
  EXPECT_EQ(post_calls, 1);
  ASSERT_EQ(t.rows().size(), 3u);
  EXPECT_EQ(t.failed(), 3);
  for (int k = 0; k < 3; ++k) {
    const SweepRow& r = t.rows()[k];
    EXPECT_EQ(r.index, k);  // rows in run order whatever order the children finish in
    EXPECT_EQ(r.values[0], std::vector<std::string>({"0.1", "0.2", "0.3"})[k]);
    EXPECT_EQ(r.status, "failed");
    EXPECT_NE(r.error.find("exit status"), std::string::npos) << r.error;
    EXPECT_NE(r.error.find("run"), std::string::npos) << r.error;  // sh's own message, from log.txt
    EXPECT_TRUE(r.scalars.empty());
  }
  EXPECT_EQ(t.columns(), (std::vector<std::string>{"run", "simulation.cfl", "status", "error"}));

  o.executable = (dir.path / "no_such_binary").string();  // cannot start: recorded, not thrown
  o.post_steps.clear();
  const SweepTable t2 = run_sweep(o);
  EXPECT_EQ(t2.failed(), 3);
  EXPECT_NE(t2.rows()[0].error.find("no_such_binary"), std::string::npos) << t2.rows()[0].error;
}

}  // namespace test_sweep
