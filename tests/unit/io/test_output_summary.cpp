// Summary JSON: escaping, null for non-finite numbers, nesting, atomic write, parse by Python.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/summary_writer.hpp"
#include "support/test_files.hpp"

namespace test_output_summary {

namespace fs = std::filesystem;
using ballista::test::slurp;
using namespace ballista;

namespace {

}  // namespace

TEST(OutputSummary, CompactDumpIsExact) {
  JsonValue j;
  j["int"] = 42;
  j["big"] = std::int64_t{9007199254740993};  // not representable as a double
  j["real"] = 0.1;
  j["whole"] = 3.0;
  j["nan"] = std::nan("");
  j["inf"] = -std::numeric_limits<double>::infinity();
  j["yes"] = true;
  j["none"] = nullptr;
  j["text"] = "q\"b\\n\nt\t\x01\x7f";
  j["list"] = std::vector<double>{1.5, std::nan(""), -2e-300};
  j["nested"]["deeper"]["k"] = "v";
  j["empty_obj"] = JsonValue::object();
  j["empty_arr"] = JsonValue::array();
  EXPECT_EQ(j.dump(-1),
            "{\"int\":42,\"big\":9007199254740993,\"real\":0.1,\"whole\":3,\"nan\":null,"
            "\"inf\":null,\"yes\":true,\"none\":null,"
            "\"text\":\"q\\\"b\\\\n\\nt\\t\\u0001\x7f\","
            "\"list\":[1.5,null,-2e-300],\"nested\":{\"deeper\":{\"k\":\"v\"}},"
            "\"empty_obj\":{},\"empty_arr\":[]}");
  EXPECT_EQ(j.at("nested").at("deeper").at("k").as_string(), "v");
  EXPECT_EQ(j.at("int").as_int(), 42);
  EXPECT_EQ(j.at("list").size(), 3u);
  EXPECT_TRUE(j.contains("yes"));
  EXPECT_FALSE(j.contains("no"));
  EXPECT_THROW(j.at("no"), Error);
  EXPECT_THROW(j.at("int").as_string(), Error);
  EXPECT_THROW(j["int"]["x"], Error);  // an integer is not an object
}

TEST(OutputSummary, InvalidUtf8IsReplacedValidKept) {
  JsonValue j = std::string("caf\xc3\xa9 \xff end");
  EXPECT_EQ(j.dump(), "\"caf\xc3\xa9 \\ufffd end\"");
}

TEST(OutputSummary, InsertionOrderAndOverwrite) {
  JsonValue j;
  j["b"] = 1;
  j["a"] = 2;
  j["b"] = "replaced";
  ASSERT_EQ(j.keys().size(), 2u);
  EXPECT_EQ(j.keys()[0], "b");
  EXPECT_EQ(j.dump(-1), "{\"b\":\"replaced\",\"a\":2}");
  JsonValue arr;
  arr.push_back(nullptr).push_back(2);  // push_back on the new null element makes it an array
  EXPECT_EQ(arr.dump(-1), "[[2]]");
}

TEST(OutputSummary, WritesAtomicallyAndPythonParsesIt) {
  ballista::test::TempDir d{"ballista_output"};
  const fs::path p = d.path / "summary.json";
  SummaryWriter s;
  s["version"] = "0.1.0";
  s["steps"] = 1234;
  s["wall_time"] = 1.25;
  s["particle_steps_per_second"] = std::numeric_limits<double>::quiet_NaN();
  JsonValue& probes = s["probes"];
  probes["tip \"x\""]["value"] = 0.5;
  probes["tip \"x\""]["series"] = std::vector<double>{0.0, 0.25, 0.5};
  JsonValue& runs = s["runs"];
  for (int k = 0; k < 2; ++k) {
    JsonValue& r = runs.push_back(JsonValue::object());
    r["k"] = k;
  }
  s.write(p.string());
  EXPECT_FALSE(fs::exists(p.string() + ".tmp"));
  const std::string text = slurp(p);
  EXPECT_NE(text.find("\"particle_steps_per_second\": null"), std::string::npos) << text;
  EXPECT_NE(text.find("\"series\": [0, 0.25, 0.5]"), std::string::npos) << text;
  EXPECT_EQ(text.back(), '\n');

  // Rewriting replaces the file in full.
  s["steps"] = 2000;
  s.write(p.string());
  EXPECT_NE(slurp(p).find("\"steps\": 2000"), std::string::npos);

#ifdef BALLISTA_PYTHON
  if (!fs::exists(BALLISTA_PYTHON)) GTEST_SKIP() << "no " << BALLISTA_PYTHON;
  const std::string cmd = std::string(BALLISTA_PYTHON) +
                          " -c \"import json,sys; d=json.load(open(sys.argv[1],encoding='utf-8')); "
                          "assert d['steps']==2000 and d['particle_steps_per_second'] is None; "
                          "assert d['probes']['tip \\\"x\\\"']['series']==[0,0.25,0.5]; "
                          "assert [r['k'] for r in d['runs']]==[0,1]\" '" +
                          p.string() + "'";
  const int rc = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << cmd;
#endif
}

}  // namespace test_output_summary
