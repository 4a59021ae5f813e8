// Atomic file writes: complete replacement, no temporary left behind, cleanup on failure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "support/test_files.hpp"

namespace test_output_atomic {

namespace fs = std::filesystem;
using ballista::test::count_tmp;
using ballista::test::slurp;
using namespace ballista;

namespace {

}  // namespace

TEST(OutputAtomic, WritesAndReplacesWithoutTemporary) {
  ballista::test::TempDir d{"ballista_output"};
  const std::string p = (d.path / "a.txt").string();
  write_file_atomic(p, "first\n");
  EXPECT_EQ(slurp(p), "first\n");
  write_file_atomic(p, std::string("second\0binary", 13));
  EXPECT_EQ(slurp(p), std::string("second\0binary", 13));
  EXPECT_EQ(count_tmp(d.path), 0);
  EXPECT_EQ(tmp_path_for(p), p + ".tmp");
}

TEST(OutputAtomic, FailsLoudlyOnMissingDirectory) {
  ballista::test::TempDir d{"ballista_output"};
  EXPECT_THROW(write_file_atomic((d.path / "no" / "such" / "file").string(), "x"), Error);
}

TEST(OutputAtomic, PathGuardCommitsOrCleansUp) {
  ballista::test::TempDir d{"ballista_output"};
  const std::string p = (d.path / "b.bin").string();
  {
    AtomicPath guard(p);
    std::ofstream(guard.tmp()) << "partial";
    // Not committed: the destructor removes the temporary, NAME never appears.
  }
  EXPECT_FALSE(fs::exists(p));
  EXPECT_EQ(count_tmp(d.path), 0);
  {
    AtomicPath guard(p);
    std::ofstream(guard.tmp()) << "complete";
    EXPECT_FALSE(fs::exists(p));
    guard.commit();
  }
  EXPECT_EQ(slurp(p), "complete");
  EXPECT_EQ(count_tmp(d.path), 0);
  // A previous complete file survives an abandoned rewrite.
  {
    AtomicPath guard(p);
    std::ofstream(guard.tmp()) << "half";
  }
  EXPECT_EQ(slurp(p), "complete");
}

TEST(OutputAtomic, CommitOfMissingTemporaryThrows) {
  ballista::test::TempDir d{"ballista_output"};
  EXPECT_THROW(commit_atomic((d.path / "x.tmp").string(), (d.path / "x").string()), Error);
}

}  // namespace test_output_atomic
