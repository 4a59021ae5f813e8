// History CSV: header, exact number round trip, rows visible while the writer is still open.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/history_writer.hpp"
#include "support/test_files.hpp"

namespace test_output_history {

namespace fs = std::filesystem;
using namespace ballista;

namespace {

std::vector<std::string> lines_of(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<double> parse_row(const std::string& line) {
  std::vector<double> v;
  const char* s = line.c_str();
  while (*s) {
    char* end = nullptr;
    v.push_back(std::strtod(s, &end));
    EXPECT_NE(end, s) << "unparsable number in '" << line << "'";
    if (end == s) break;
    s = end;
    if (*s == ',') ++s;
  }
  return v;
}

}  // namespace

TEST(OutputHistory, RoundTripsNumbersExactly) {
  ballista::test::TempDir d{"ballista_output"};
  const fs::path p = d.path / "history.csv";
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<std::vector<double>> rows = {
      {0.0, 0.1, 1.0 / 3.0},
      {1e-300, -2.5e17, 123456789.123456789},
      {std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(), -0.0},
      {std::nan(""), inf, -inf},
  };
  {
    HistoryWriter h(p.string(), {"time", "probe,1", "e\"q"});
    for (size_t r = 0; r < rows.size(); ++r) {
      h.row(rows[r]);
      // Flushed after each row: the header plus r+1 complete lines are already on disk.
      EXPECT_EQ(lines_of(p).size(), r + 2);
    }
    EXPECT_THROW(h.row({1.0, 2.0}), Error);
  }
  const auto lines = lines_of(p);
  ASSERT_EQ(lines.size(), rows.size() + 1);
  EXPECT_EQ(lines[0], "time,\"probe,1\",\"e\"\"q\"");
  EXPECT_EQ(lines[1], "0,0.1,0.3333333333333333");
  for (size_t r = 0; r < rows.size(); ++r) {
    const auto v = parse_row(lines[r + 1]);
    ASSERT_EQ(v.size(), rows[r].size());
    for (size_t k = 0; k < v.size(); ++k) {
      if (std::isnan(rows[r][k])) {
        EXPECT_TRUE(std::isnan(v[k]));
      } else {
        EXPECT_EQ(v[k], rows[r][k]) << "row " << r << " column " << k;
        EXPECT_EQ(std::signbit(v[k]), std::signbit(rows[r][k]));
      }
    }
  }
}

TEST(OutputHistory, RejectsBadSetup) {
  ballista::test::TempDir d{"ballista_output"};
  EXPECT_THROW(HistoryWriter((d.path / "no" / "h.csv").string(), {"t"}), Error);
  EXPECT_THROW(HistoryWriter((d.path / "h.csv").string(), {}), Error);
}

TEST(OutputHistory, ResumeWithOtherColumnsNamesTheDifference) {
  // A checkpoint's history written with other columns (an older version, or probes changed by
  // --set) cannot be continued; the error names what differs. The same columns continue.
  ballista::test::TempDir d{"ballista_output"};
  const std::string path = (d.path / "h.csv").string();
  long long bytes = 0;
  {
    HistoryWriter w(path, {"time", "kinetic_energy", "old_probe"});
    w.row({0.0, 1.0, 2.0});
    bytes = w.bytes();
    w.row({1.0, 3.0, 4.0});  // after the checkpoint: dropped on resume
  }
  try {
    HistoryWriter w(path, {"time", "kinetic_energy", "boundary_work"}, bytes);
    FAIL() << "resumed a history with other columns";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("this run adds: boundary_work"), std::string::npos) << m;
    EXPECT_NE(m.find("this run does not write: old_probe"), std::string::npos) << m;
  }
  {
    HistoryWriter w(path, {"time", "kinetic_energy", "old_probe"}, bytes);
    w.row({2.0, 5.0, 6.0});
  }
  const auto lines = lines_of(path);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[2], "2,5,6");
}

}  // namespace test_output_history
