// make_penetration_plots (run/penetration_plots.hpp) through the shared launcher
// (io/python_tool.hpp): a run folder without history.csv is reported with the script's exit
// status, and a missing interpreter is named. The figures themselves are checked by
// tests/plots/check_penetration_plots.py.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "io/python_tool.hpp"
#include "run/penetration_plots.hpp"
#include "support/test_files.hpp"

namespace test_penetration_plots {

using namespace ballista;

TEST(PenetrationPlots, FolderWithoutHistoryIsAnError) {
  test::TempDir dir("pen_plots");
  const std::string err = make_penetration_plots(dir.path.string());
  EXPECT_NE(err.find("plot_penetration.py"), std::string::npos) << err;
  EXPECT_NE(err.find("failed with status 2"), std::string::npos) << err;  // the script's "no history.csv" status
}

TEST(PenetrationPlots, MissingInterpreterIsNamed) {
  test::TempDir dir("pen_plots");
  ::setenv("BALLISTA_PYTHON", "/nonexistent/python3", 1);
  const std::string err = make_penetration_plots(dir.path.string());
  EXPECT_EQ(python_interpreter(), "/nonexistent/python3");
  ::unsetenv("BALLISTA_PYTHON");
  EXPECT_NE(err.find("/nonexistent/python3 (BALLISTA_PYTHON) does not exist"), std::string::npos) << err;
  EXPECT_NE(err.find("the penetration plot needs"), std::string::npos) << err;
}

TEST(PythonTool, QuotesShellWords) {
  EXPECT_EQ(shell_quote("a b"), "'a b'");
  EXPECT_EQ(shell_quote("it's"), "'it'\\''s'");
}

}  // namespace test_penetration_plots
