// Drive decks (driver/drive_deck), F-table files (driver/ftable_csv), perturbations
// (driver/perturb) and the outputs of `ballista drive` (driver/drive_run).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.hpp"
#include "driver/drive_deck.hpp"
#include "driver/drive_run.hpp"
#include "driver/ftable_csv.hpp"
#include "driver/perturb.hpp"
#include "support/test_files.hpp"

namespace test_drive_deck {

using namespace ballista;
using ballista::test::slurp;
using ballista::test::TempDir;

namespace {

const std::string kMaterial = R"(materials:
  steel: {model: linear_elastic, density: 7850, youngs_modulus: 200e9, poisson_ratio: 0.3}
)";

/// The DeckError message of parsing `text` (base dir `dir`), or "(no error)".
std::string deck_error(const std::string& text, const std::string& dir = ".") {
  try {
    parse_drive_deck(text, "d.yaml", {}, dir);
  } catch (const DeckError& e) {
    return e.what();
  }
  return "(no error)";
}

void write(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

#define EXPECT_HAS(haystack, needle) EXPECT_NE((haystack).find(needle), std::string::npos) << (haystack)

}  // namespace

// Every shipped drive deck parses, drives a program, and its resolved form resolves to itself.
TEST(DriveDeck, ExampleDecksParseAndResolveToThemselves) {
  const auto dir = std::filesystem::path(BALLISTA_SOURCE_DIR) / "examples";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() != ".yaml" || name.rfind("drive_", 0) != 0) continue;
    ++count;
    DriveDeck d;
    try {
      d = read_drive_deck(entry.path().string());
    } catch (const Error& e) {
      ADD_FAILURE() << name << ": " << e.what();
      continue;
    }
    EXPECT_TRUE(!d.program.table.empty() || !d.program.legs.empty()) << name;
    const DriveDeck again = parse_drive_deck(d.resolved_yaml, "resolved.yaml", {}, dir.string());
    auto body = [](const std::string& s) { return s.substr(s.find('\n') + 1); };
    EXPECT_EQ(body(again.resolved_yaml), body(d.resolved_yaml)) << name;
  }
  EXPECT_GE(count, 2);
}

TEST(DriveDeck, LegsAreRead) {
  const DriveDeck d = parse_drive_deck(kMaterial + R"(drive:
  legs:
    - {duration: 1, steps: 100, strain: {11: -0.01, 12: 0.002}, stress: {22: 0, 33: -1e6}}
    - {duration: 2, steps: 5, stress: {11: 0}}
  stress_tolerance: 1e-9
)",
                                       "d.yaml");
  EXPECT_EQ(d.material.name, "steel");
  ASSERT_EQ(d.program.legs.size(), 2u);
  const DriveLeg& a = d.program.legs[0];
  EXPECT_EQ(a.duration, 1.0);
  EXPECT_EQ(a.steps, 100);
  EXPECT_FALSE(a.stress_controlled[0]);
  EXPECT_EQ(a.value[0], -0.01);
  EXPECT_TRUE(a.stress_controlled[1]);
  EXPECT_TRUE(a.stress_controlled[2]);
  EXPECT_EQ(a.value[2], -1e6);
  EXPECT_EQ(a.value[5], 0.002);  // 12 is the last component
  EXPECT_FALSE(a.stress_controlled[3]);
  EXPECT_EQ(a.value[3], 0.0);  // not given: strain-controlled, zero increment
  EXPECT_TRUE(d.program.legs[1].stress_controlled[0]);
  EXPECT_EQ(d.program.stress_tolerance, 1e-9);
  EXPECT_EQ(d.program.record_every, 1);
}

TEST(DriveDeck, InlineTableAndOverrides) {
  const std::string text = kMaterial + R"(drive:
  table:
    - [0, 1, 0, 0, 0, 1, 0, 0, 0, 1]
    - [1, 1.01, 0, 0, 0, 1, 0, 0, 0, 1, 90, 0, 0, 1]
  substeps: 10
)";
  const DriveDeck d = parse_drive_deck(text, "d.yaml", {"drive.substeps=20", "drive.record_every=5"});
  ASSERT_EQ(d.program.table.size(), 2u);
  EXPECT_EQ(d.program.table[1].F(0, 0), 1.01);
  EXPECT_EQ(d.program.table[1].angle_deg, 90.0);
  EXPECT_EQ(d.program.substeps, 20);
  EXPECT_EQ(d.program.record_every, 5);
  EXPECT_TRUE(d.table_file.empty());
}

TEST(DriveDeck, Errors) {
  EXPECT_HAS(deck_error("drive: {legs: [{duration: 1, steps: 1}]}\n"), "missing required key 'materials'");
  EXPECT_HAS(deck_error(R"(materials:
  a: {model: linear_elastic, density: 1, bulk_modulus: 1, shear_modulus: 1}
  b: {model: linear_elastic, density: 1, bulk_modulus: 1, shear_modulus: 1}
drive: {legs: [{duration: 1, steps: 1}]}
)"),
             "d.yaml:1:1: 'materials': expected exactly one material in a drive deck");
  // Material errors are those of the run decks (shared reader).
  EXPECT_HAS(deck_error(R"(materials:
  a: {model: linear_elastik, density: 1}
drive: {legs: [{duration: 1, steps: 1}]}
)"),
             "did you mean 'linear_elastic'?");
  EXPECT_HAS(deck_error(kMaterial + "drive: {}\n"), "expected a deformation program in drive");
  EXPECT_HAS(deck_error(kMaterial + "drive: {table: x.csv, legs: [{duration: 1, steps: 1}]}\n"),
             "expected either table or legs in drive, not both");
  EXPECT_HAS(
      deck_error(kMaterial + "drive:\n  legs:\n    - {duration: 1, steps: 1, strain: {11: 1}, stress: {11: 0}}\n"),
      "d.yaml:5:61: 'drive.legs.0.stress.11': component 11 is both strain- and stress-controlled");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  legs:\n    - {duration: 1, steps: 1, strain: {21: 0.1}}\n"),
             "'drive.legs.0.strain.21': write the symmetric component 21 as 12");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  legs:\n    - {duration: 1, steps: 1, strain: {14: 0.1}}\n"),
             "unknown key '14' in drive.legs.0.strain");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  legs:\n    - {duration: 0, steps: 1}\n"),
             "'drive.legs.0.duration': expected a number > 0 (s), got 0");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  legs:\n    - {duration: 1, steps: 0}\n"),
             "'drive.legs.0.steps': expected an integer in 1..100000000");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  legs: [{duration: 1, steps: 1}]\n  substeps: 3\n"),
             "'drive.substeps': 'substeps' applies to an F-table, not to legs");
  EXPECT_HAS(deck_error(kMaterial +
                        "drive:\n  table: [[0,1,0,0,0,1,0,0,0,1],[1,1,0,0,0,1,0,0,0,1]]\n  stress_tolerance: 1e-8\n"),
             "'stress_tolerance' applies to legs");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table:\n    - [0,1,0,0,0,1,0,0,0,1]\n    - [1,1,0,0,0,1,0,0]\n"),
             "d.yaml:6:7: 'drive.table.1': expected a row of 10 or 14 numbers");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table:\n    - [0,1,0,0,0,1,0,0,0,1]\n    - [0,1,0,0,0,1,0,0,0,1]\n"),
             "d.yaml:6:7: 'drive.table.1': expected times strictly increasing; 0 follows 0");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table:\n    - [0,1,0,0,0,1,0,0,0,1]\n    - [1,-1,0,0,0,1,0,0,0,1]\n"),
             "'drive.table.1': expected det F >= 1e-6 (a volume ratio), got -1");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table:\n    - [0,1,0,0,0,1,0,0,0,1]\n    - [1,x,0,0,0,1,0,0,0,1]\n"),
             "'drive.table.1.1': expected a number, got 'x'");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table: [[0,1,0,0,0,1,0,0,0,1]]\n"), "expected at least 2 rows");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table: missing.csv\n", "/nonexistent_dir"),
             "d.yaml:4:10: 'drive.table': cannot open the F-table file 'missing.csv' (looked for "
             "/nonexistent_dir/missing.csv");
  EXPECT_HAS(deck_error(kMaterial + "drive:\n  table: [[0,1,0,0,0,1,0,0,0,1],[1,2,0,0,0,1,0,0,0,1]]\n  noise: 5\n"),
             "'drive.noise': noise makes det F");
}

TEST(FTableCsv, ReadsHeaderCommentsAndBlanks) {
  TempDir dir;
  const auto p = dir.path / "t.csv";
  write(p,
        "# comment\n\nt,F11,F12,F13,F21,F22,F23,F31,F32,F33\n0,1,0,0,0,1,0,0,0,1\n"
        "0.5 1.25 0 0 0 1 0 0 0 1\n1.0000000000000002,1.2500000000000002,0,0,0,1,0,0,0,1\n");
  const FTableFile f = read_ftable_csv(p.string(), "drive.table");
  ASSERT_EQ(f.rows.size(), 3u);
  EXPECT_EQ(f.lines, (std::vector<int>{4, 5, 6}));
  EXPECT_EQ(f.rows[1].F(0, 0), 1.25);
  // Full precision: the last bit survives.
  EXPECT_EQ(f.rows[2].t, std::nextafter(1.0, 2.0));
  EXPECT_EQ(f.rows[2].F(0, 0), std::nextafter(1.25, 2.0));
}

TEST(FTableCsv, ErrorsNameFileLineAndColumn) {
  TempDir dir;
  auto err = [&](const std::string& text) {
    const auto p = dir.path / "t.csv";
    write(p, text);
    try {
      read_ftable_csv(p.string(), "drive.table");
    } catch (const DeckError& e) {
      return std::string(e.what()).substr(p.string().size());
    }
    return std::string("(no error)");
  };
  const std::string row0 = "0,1,0,0,0,1,0,0,0,1\n";
  EXPECT_HAS(err(row0 + "1,1,0,0,0,1,0,0,0,zz\n"), ":2:19: 'drive.table': expected a number, got 'zz'");
  EXPECT_HAS(err(row0 + "1,1,0,0,0,1,0,0,0\n"), ":2:1: 'drive.table': expected 10 numbers like the rows above");
  EXPECT_HAS(err("0,1,0,0\n"), ":1:1: 'drive.table': expected 10 or 14 numbers");
  EXPECT_HAS(err("t,F11,F12,F13,F21,F22,F23,F31,F32,G33\n" + row0), ":1:35: 'drive.table': expected the header t, F11");
  EXPECT_HAS(err(row0 + "0,1,0,0,0,1,0,0,0,1\n"),
             ":2:1: 'drive.table': row at t = 0: expected times strictly increasing");
  EXPECT_HAS(err(row0), "expected at least 2 rows");
  EXPECT_HAS(err("0,1,0,0,0,1,0,0,0,1,45,0,0,1\n1,1,0,0,0,1,0,0,0,1,0,0,0,1\n"),
             ":1:1: 'drive.table': row at t = 0: expected rotation angle 0 in the first row");
}

// scale 1 and noise 0 change nothing; scale 0 turns every F into I; noise is reproducible for a
// seed, differs between seeds, and changes each increment entry by at most noise x its size.
TEST(Perturb, ScaleAndNoise) {
  std::vector<FTableRow> rows(4);
  for (int k = 0; k < 4; ++k) {
    rows[k].t = k;
    rows[k].F = Mat3::diag(1.0 + 0.01 * k, 1.0 - 0.003 * k, 1.0);
    rows[k].F(0, 1) = 0.002 * k;
  }
  auto same = [](const std::vector<FTableRow>& a, const std::vector<FTableRow>& b) {
    for (size_t k = 0; k < a.size(); ++k)
      for (int e = 0; e < 9; ++e)
        if (a[k].F.a[e] != b[k].F.a[e]) return false;
    return true;
  };
  EXPECT_TRUE(same(perturb_table(rows, 1.0, 0.0, 7), rows));
  for (const auto& r : perturb_table(rows, 0.0, 0.0, 7))
    for (int e = 0; e < 9; ++e) EXPECT_EQ(r.F.a[e], Mat3::identity().a[e]);
  const auto half = perturb_table(rows, 0.5, 0.0, 0);
  EXPECT_DOUBLE_EQ(half[2].F(0, 0), 1.01);
  const auto n1 = perturb_table(rows, 1.0, 0.1, 42), n2 = perturb_table(rows, 1.0, 0.1, 42),
             n3 = perturb_table(rows, 1.0, 0.1, 43);
  EXPECT_TRUE(same(n1, n2));
  EXPECT_FALSE(same(n1, n3));
  EXPECT_FALSE(same(n1, rows));
  for (size_t k = 1; k < rows.size(); ++k) {
    const Mat3 G = rows[k].F * inverse(rows[k - 1].F) - Mat3::identity();
    const Mat3 Gp = n1[k].F * inverse(n1[k - 1].F) - Mat3::identity();
    for (int e = 0; e < 9; ++e) EXPECT_LE(std::abs(Gp.a[e] - G.a[e]), 0.1 * std::abs(G.a[e]) + 1e-15) << k << e;
  }
  EXPECT_EQ(n1[3].t, 3.0);
  EXPECT_THROW(perturb_table(rows, -200.0, 0.0, 0), Error);
}

// run_drive writes resolved.yaml, history.csv (a header and one row per record) and summary.json.
TEST(DriveRun, WritesOutputs) {
  TempDir dir;
  write(dir.path / "f.csv", "t F11 F12 F13 F21 F22 F23 F31 F32 F33\n0 1 0 0 0 1 0 0 0 1\n1 1.001 0 0 0 1 0 0 0 1\n");
  write(dir.path / "d.yaml", kMaterial + "drive: {table: f.csv, substeps: 4}\n");
  const DriveDeck d = read_drive_deck((dir.path / "d.yaml").string());
  EXPECT_EQ(d.table_file, (dir.path / "f.csv").string());
  const auto out = dir.path / "out";
  const DriveRunResult r = run_drive(d, out.string());
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.steps, 4);
  const std::string hist = slurp(out / "history.csv");
  EXPECT_EQ(hist.rfind("step,t,F11,", 0), 0u);
  EXPECT_EQ(std::count(hist.begin(), hist.end(), '\n'), 6);  // header + 5 records
  const std::string sum = slurp(out / "summary.json");
  EXPECT_HAS(sum, "\"status\": \"completed\"");
  EXPECT_HAS(sum, "\"kind\": \"table\"");
  EXPECT_HAS(slurp(out / "resolved.yaml"),
             "table: " + std::filesystem::absolute(dir.path / "f.csv").lexically_normal().string());
  EXPECT_EQ(ballista::test::count_tmp(out), 0);
}

// A reproduced failure: status "failed", the error, and the history up to the failing step
// (its row holds the non-finite stress the model returned).
TEST(DriveRun, FailureIsReportedWithHistory) {
  TempDir dir;
  const DriveDeck d = parse_drive_deck(kMaterial + R"(drive:
  table: [[0,1,0,0,0,1,0,0,0,1], [1,1.001,0,0,0,1,0,0,0,1], [2,1e300,0,0,0,1,0,0,0,1]]
)",
                                       "d.yaml");
  const DriveRunResult r = run_drive(d, dir.path.string());
  EXPECT_FALSE(r.ok);
  EXPECT_HAS(r.error, "non-finite stress");
  EXPECT_EQ(r.steps, 1);
  EXPECT_EQ(r.records, 3u);
  EXPECT_EQ(r.last.iterations, -1);
  EXPECT_FALSE(std::isfinite(r.last.sigma(0, 0)));
  EXPECT_HAS(slurp(dir.path / "summary.json"), "\"status\": \"failed\"");
}

}  // namespace test_drive_deck
