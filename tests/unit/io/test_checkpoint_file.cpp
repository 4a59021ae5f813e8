// Checkpoint files (io/checkpoint_file.hpp, core/state_archive.hpp): an archive reads back exactly
// (every bit of every double, including infinities and NaN payloads; empty arrays; texts with
// line breaks and NUL bytes), a missing or mis-sized key is an error that names it, point fields
// round-trip through a FieldStore, and only the newest checkpoints are kept.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/error.hpp"
#include "core/state_archive.hpp"
#include "io/checkpoint_file.hpp"
#include "support/test_files.hpp"

namespace test_checkpoint_file {

using namespace ballista;
using ballista::test::TempDir;

namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CheckpointFile, ArchiveReadsBackBitForBit) {
  TempDir dir("ckpt");
  StateArchive a;
  const double nan_payload = [] {
    std::uint64_t bits = 0x7ff8000000000123ULL;
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }();
  const std::vector<double> reals = {0.1, -0.0, 1e-308, 4.9e-324, std::numeric_limits<double>::infinity(),
                                     -std::numeric_limits<double>::infinity(), nan_payload, 1.0 / 3.0};
  a.put("mpm.values", reals);
  a.put("empty", std::vector<double>{});
  a.put("run.counters", std::vector<std::int64_t>{-1, 0, std::numeric_limits<std::int64_t>::max()});
  a.put_text("run.deck", std::string("a: 1\nb: [2, 3]\n\0tail", 18));
  a.put_text("blank", "");
  const std::string path = checkpoint_path(dir.path.string(), 42);
  write_checkpoint_file(path, a);
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  const StateArchive b = read_checkpoint_file(path);
  const auto& r = b.reals("mpm.values", reals.size());
  for (std::size_t k = 0; k < reals.size(); ++k) EXPECT_TRUE(same_bits(r[k], reals[k])) << k;
  EXPECT_TRUE(b.reals("empty").empty());
  EXPECT_EQ(b.ints("run.counters"), (std::vector<std::int64_t>{-1, 0, std::numeric_limits<std::int64_t>::max()}));
  EXPECT_EQ(b.text("run.deck"), std::string("a: 1\nb: [2, 3]\n\0tail", 18));
  EXPECT_EQ(b.text("blank"), "");
  EXPECT_EQ(read_checkpoint_text(path, "run.deck"), b.text("run.deck"));
}

TEST(CheckpointFile, MissingAndMisSizedKeysAreNamed) {
  StateArchive a;
  a.put("pd.time", std::vector<double>{1.0, 2.0});
  EXPECT_NE(error_of([&] { a.real("pd.time"); }).find("'pd.time' holds 2 values, 1 were expected"), std::string::npos);
  EXPECT_NE(error_of([&] { a.ints("pd.steps"); }).find("no integer array 'pd.steps'"), std::string::npos);
  EXPECT_NE(error_of([&] { a.text("run.deck"); }).find("no text 'run.deck'"), std::string::npos);
}

TEST(CheckpointFile, AGroupOfScalarsReadsBackIntoItsVariablesInOrder) {
  // The solvers save scalar groups as one array and read them back with get_into: each value
  // lands in the variable at its place, bit for bit, and a group of another length is refused
  // with its key (a checkpoint of another version).
  StateArchive a;
  const double inf = std::numeric_limits<double>::infinity();
  a.put("mpm.work", std::vector<double>{1.5, -0.0, inf, 3e-300});
  double w = 0, x = 1, y = 2, z = 3;
  a.get_into("mpm.work", {&w, &x, &y, &z});
  EXPECT_TRUE(same_bits(w, 1.5));
  EXPECT_TRUE(same_bits(x, -0.0));
  EXPECT_TRUE(same_bits(y, inf));
  EXPECT_TRUE(same_bits(z, 3e-300));
  EXPECT_NE(error_of([&] { a.get_into("mpm.work", {&w, &x, &y}); }).find("'mpm.work' holds 4 values, 3 were expected"),
            std::string::npos);
}

TEST(CheckpointFile, NotACheckpointIsRefusedWithItsPath) {
  TempDir dir("ckpt");
  const auto path = (dir.path / "checkpoints" / "checkpoint_000000000001.h5").string();
  std::filesystem::create_directories(dir.path / "checkpoints");
  std::ofstream(path) << "not HDF5";
  const std::string msg = error_of([&] { read_checkpoint_file(path); });
  EXPECT_NE(msg.find("cannot read checkpoint '" + path + "'"), std::string::npos) << msg;
  // The newest readable one is chosen; with none readable the error says so.
  EXPECT_NE(error_of([&] { newest_checkpoint(dir.path.string()); }).find("no checkpoint"), std::string::npos);
  StateArchive a;
  a.put_text("run.deck", "deck text");
  write_checkpoint_file(checkpoint_path(dir.path.string(), 0), a);
  const auto [found, deck] = newest_checkpoint(dir.path.string());
  EXPECT_EQ(found, checkpoint_path(dir.path.string(), 0));  // step 1 is unreadable: skipped
  EXPECT_EQ(deck, "deck text");
}

TEST(CheckpointFile, FieldStoreRoundTrip) {
  FieldStore s;
  s.add_real("x", 3, "m");
  s.add_int("id", 1, "1");
  s.resize(4);
  for (int k = 0; k < 12; ++k) s.real("x")[k] = 0.5 * k;
  for (int k = 0; k < 4; ++k) s.ints("id")[k] = 10 + k;
  StateArchive a;
  a.put_fields("points.", s);
  FieldStore t = s.empty_like();
  a.get_fields("points.", t);
  ASSERT_EQ(t.size(), 4);
  for (int k = 0; k < 12; ++k) EXPECT_EQ(t.real("x")[k], 0.5 * k);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(t.ints("id")[k], 10 + k);
  // A store that declares a field the archive does not hold (another deck's materials).
  FieldStore u = s.empty_like();
  u.add_real("eqps", 1, "1");
  EXPECT_NE(error_of([&] { a.get_fields("points.", u); }).find("'points.eqps'"), std::string::npos);
}

TEST(CheckpointFile, OnlyTheNewestAreKeptAndTemporaryFilesIgnored) {
  TempDir dir("ckpt");
  StateArchive a;
  for (long step : {5L, 100L, 20L, 7L}) write_checkpoint_file(checkpoint_path(dir.path.string(), step), a);
  std::ofstream(checkpoint_path(dir.path.string(), 200) + ".tmp") << "partial";
  auto all = list_checkpoints(dir.path.string());
  ASSERT_EQ(all.size(), 4u);
  EXPECT_EQ(all.back(), checkpoint_path(dir.path.string(), 100));  // by step, not by name length
  EXPECT_EQ(prune_checkpoints(dir.path.string(), 2), 2);
  all = list_checkpoints(dir.path.string());
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0], checkpoint_path(dir.path.string(), 20));
  EXPECT_EQ(all[1], checkpoint_path(dir.path.string(), 100));
}

namespace {

/// Flips one bit of the first occurrence of `value`'s bytes in the file at `path`.
void flip_bit_of(const std::string& path, double value) {
  std::string bytes = ballista::test::slurp(path);
  char pattern[sizeof value];
  std::memcpy(pattern, &value, sizeof value);
  const std::size_t at = bytes.find(std::string(pattern, sizeof value));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 3] = static_cast<char>(bytes[at + 3] ^ 0x10);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

StateArchive deck_archive(long step) {
  StateArchive a;
  std::vector<double> mass(1000);
  for (std::size_t k = 0; k < mass.size(); ++k) mass[k] = 0.5 + static_cast<double>(k);
  a.put("points.mass", mass);
  a.put_text("run.deck", "simulation: {end_time: 1}\n");
  a.put_int("run.step", step);
  return a;
}

}  // namespace

// A bit flipped in a checkpoint's values (a bad disk block, a partial copy) is found when the file
// is read, by the checksum each dataset carries (core/checksum.hpp), and named.
TEST(CheckpointFile, ADamagedValueIsFoundAndNamed) {
  TempDir dir("ckpt_damaged");
  const std::string path = checkpoint_path(dir.path.string(), 3);
  write_checkpoint_file(path, deck_archive(3));
  EXPECT_NO_THROW(read_checkpoint_file(path));
  flip_bit_of(path, 700.5);
  const std::string err = error_of([&] { read_checkpoint_file(path); });
  EXPECT_NE(err.find("'points.mass' is damaged"), std::string::npos) << err;
  EXPECT_NE(err.find(path), std::string::npos) << err;
}

TEST(CheckpointFile, ACheckpointUnderAnotherStepsNameIsRefused) {
  TempDir dir("ckpt_swapped");
  const std::string path = checkpoint_path(dir.path.string(), 7);
  write_checkpoint_file(path, deck_archive(5));
  const std::string err = error_of([&] { read_checkpoint_file(path); });
  EXPECT_NE(err.find("holds step 5 under the name of step 7"), std::string::npos) << err;
}

TEST(CheckpointFile, ADamagedNewestCheckpointGivesWayToThePreviousOne) {
  TempDir dir("ckpt_fallback");
  const std::string older = checkpoint_path(dir.path.string(), 10), newer = checkpoint_path(dir.path.string(), 20);
  write_checkpoint_file(older, deck_archive(10));
  write_checkpoint_file(newer, deck_archive(20));
  EXPECT_EQ(newest_checkpoint(dir.path.string()).first, newer);
  flip_bit_of(newer, 42.5);
  EXPECT_EQ(newest_checkpoint(dir.path.string()).first, older);
  flip_bit_of(older, 42.5);
  const std::string err = error_of([&] { newest_checkpoint(dir.path.string()); });
  EXPECT_NE(err.find("no checkpoint of"), std::string::npos) << err;
  EXPECT_NE(err.find("damaged"), std::string::npos) << err;
}

}  // namespace test_checkpoint_file
