// A results folder held by one run (io/run_folder.hpp): a second holder is refused while the
// first lives, a new run removes exactly the files the previous one listed (never a user's own),
// a folder holding other files is refused unless overwritten, and a restart keeps what is there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/history_writer.hpp"
#include "io/run_folder.hpp"
#include "support/test_files.hpp"

namespace test_run_folder {

namespace fs = std::filesystem;
using namespace ballista;
using ballista::test::slurp;
using ballista::test::TempDir;
using ballista::test::error_of;

namespace {

void touch(const fs::path& p, const std::string& text = "x") {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

}  // namespace

TEST(RunFolder, ASecondRunIntoAHeldFolderIsRefusedUntilTheFirstEnds) {
  TempDir d{"run_folder_lock"};
  const std::string dir = (d.path / "out").string();
  {
    RunFolder first(dir, RunFolder::Mode::NewRun);
    // flock conflicts between two open files of one process as between processes.
    const std::string err = error_of([&] { RunFolder second(dir, RunFolder::Mode::NewRun); });
    EXPECT_NE(err.find("is in use by another Ballista run"), std::string::npos) << err;
    EXPECT_NE(err.find("pid"), std::string::npos) << err;  // who holds it
    const std::string restart = error_of([&] { RunFolder again(dir, RunFolder::Mode::Continue); });
    EXPECT_NE(restart.find("in use"), std::string::npos) << restart;
  }
  EXPECT_NO_THROW(RunFolder(dir, RunFolder::Mode::NewRun));  // released with the first
}

TEST(RunFolder, ANewRunRemovesExactlyTheFilesThePreviousRunListed) {
  TempDir d{"run_folder_manifest"};
  const fs::path dir = d.path / "out";
  {
    RunFolder run(dir.string(), RunFolder::Mode::NewRun);
    write_file_atomic((dir / "summary.json").string(), "{}");
    HistoryWriter h((dir / "history.csv").string(), {"time"});
    fs::create_directories(dir / "checkpoints");
    AtomicPath ck((dir / "checkpoints" / "checkpoint_000000000001.h5").string());
    std::ofstream(ck.tmp()) << "state";
    ck.commit();
    note_output_file((dir / "figure.png").string());  // a figure a Python tool draws
    touch(dir / "figure.png");
    touch(d.path / "elsewhere.txt");  // outside the folder: not Ballista's to list
    note_output_file((d.path / "elsewhere.txt").string());
  }
  // The user's own files in the folder, one named like an output's temporary file, one like an
  // output the run did not write.
  touch(dir / "notes.tmp", "mine");
  touch(dir / "fragments.csv", "mine too");
  touch(dir / "summary.json.tmp", "left by a killed write");
  RunFolder next(dir.string(), RunFolder::Mode::NewRun);
  EXPECT_EQ(next.removed(), 4);  // summary.json, history.csv, the checkpoint, the figure
  for (const char* gone : {"summary.json", "history.csv", "checkpoints/checkpoint_000000000001.h5", "figure.png",
                           "summary.json.tmp"})
    EXPECT_FALSE(fs::exists(dir / gone)) << gone;
  EXPECT_EQ(slurp(dir / "notes.tmp"), "mine");
  EXPECT_EQ(slurp(dir / "fragments.csv"), "mine too");
  EXPECT_TRUE(fs::exists(d.path / "elsewhere.txt"));
  // The new manifest starts empty of names.
  const std::string manifest = slurp(dir / kRunManifest);
  EXPECT_EQ(manifest.find("summary.json"), std::string::npos) << manifest;
}

TEST(RunFolder, AFolderWithOtherFilesIsRefusedUnlessOverwritten) {
  TempDir d{"run_folder_foreign"};
  touch(d.path / "notes.tmp", "mine");
  touch(d.path / "history.csv", "not Ballista's");
  const std::string err = error_of([&] { RunFolder run(d.path.string(), RunFolder::Mode::NewRun); });
  EXPECT_NE(err.find("holds no Ballista run"), std::string::npos) << err;
  EXPECT_NE(err.find("--overwrite"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(d.path / kRunManifest));  // nothing written when refused
  // Overwritten: only the names Ballista writes go (as an older Ballista without a manifest left
  // them); the user's notes stay.
  RunFolder run(d.path.string(), RunFolder::Mode::NewRun, true);
  EXPECT_FALSE(fs::exists(d.path / "history.csv"));
  EXPECT_EQ(slurp(d.path / "notes.tmp"), "mine");
}

TEST(RunFolder, AResultsFolderOfAnOlderBallistaIsTakenWithoutOverwrite) {
  TempDir d{"run_folder_legacy"};
  for (const char* f : {"resolved.yaml", "history.csv", "summary.json", "particles_000000.h5", "particles.xdmf"})
    touch(d.path / f);
  touch(d.path / "notes.tmp", "mine");
  RunFolder run(d.path.string(), RunFolder::Mode::NewRun);
  EXPECT_EQ(run.removed(), 5);
  EXPECT_EQ(slurp(d.path / "notes.tmp"), "mine");
}

TEST(RunFolder, ARestartKeepsTheFilesAndAddsToTheList) {
  TempDir d{"run_folder_continue"};
  const fs::path dir = d.path / "out";
  {
    RunFolder run(dir.string(), RunFolder::Mode::NewRun);
    write_file_atomic((dir / "history.csv").string(), "t\n");
  }
  {
    RunFolder again(dir.string(), RunFolder::Mode::Continue);
    EXPECT_TRUE(fs::exists(dir / "history.csv"));
    write_file_atomic((dir / "particles_000003.h5").string(), "p");
    write_file_atomic((dir / "history.csv").string(), "t\n1\n");  // listed once
  }
  const std::string manifest = slurp(dir / kRunManifest);
  EXPECT_EQ(manifest.find("history.csv"), manifest.rfind("history.csv")) << manifest;
  RunFolder next(dir.string(), RunFolder::Mode::NewRun);
  EXPECT_EQ(next.removed(), 2);
  EXPECT_FALSE(fs::exists(dir / "particles_000003.h5"));
}

TEST(RunFolder, AManifestNamingFilesOutsideTheFolderIsNotFollowed) {
  TempDir d{"run_folder_escape"};
  const fs::path dir = d.path / "out";
  touch(d.path / "precious.txt", "keep");
  touch(dir / kRunManifest, "# a damaged or hostile list\n../precious.txt\n/etc/hostname\nsub/../../precious.txt\n");
  RunFolder run(dir.string(), RunFolder::Mode::NewRun);
  EXPECT_EQ(run.removed(), 0);
  EXPECT_EQ(slurp(d.path / "precious.txt"), "keep");
}

}  // namespace test_run_folder
