// Issue 11 regressions in the deck layer: what a hostile user found. Every case is an error that
// names the cause, never a silently ignored input, a huge echo or a huge allocation.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "driver/drive_deck.hpp"
#include "support/test_files.hpp"

namespace test_deck_hostile {

namespace fs = std::filesystem;
using namespace ballista;

namespace {

const std::string kDeck =
    "simulation: {dimension: plane_strain, end_time: 1.0e-3}\n"
    "grid: {lower: [0, 0], upper: [1, 1], cell_size: 0.125}\n"
    "materials:\n  m: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25}\n"
    "bodies:\n  - {name: b, material: m, shape: {type: box, lower: [0.25, 0.25], upper: [0.5, 0.5]}}\n";

std::string error_of(const std::string& text) {
  try {
    parse_deck(text, "hostile.yaml");
  } catch (const DeckError& e) {
    return e.what();
  }
  return "";
}

/// An axisymmetric deck whose jet reads its segments from the CSV file `table`.
std::string jet_deck(const std::string& table) {
  return "simulation: {dimension: axisymmetric, end_time: 1.0e-5}\n"
         "grid: {lower: [0, 0], upper: [0.02, 0.2], cell_size: 1.0e-3}\n"
         "materials:\n  w: {model: linear_elastic, density: 17600, youngs_modulus: 350e9, poisson_ratio: 0.3}\n"
         "bodies:\n"
         "  - {name: target, material: w, shape: {type: cylinder, center: [0, 0], axis: y, radius: 0.015, length: 0.05}}\n"
         "  - name: pen\n    material: w\n    jet: {face: [0, 0.05], insert_distance: 0.01, standoff: 0.03, file: " +
         table + "}\n";
}

}  // namespace

TEST(DeckHostile, TheCleanDeckParses) { EXPECT_NO_THROW(parse_deck(kDeck, "clean.yaml")); }

TEST(DeckHostile, SecondYamlDocumentIsAnError) {
  const std::string e = error_of(kDeck + "---\nsimulation: {end_time: 5}\n");
  EXPECT_NE(e.find("more than one YAML document"), std::string::npos) << e;
  EXPECT_NE(e.find("hostile.yaml:7:"), std::string::npos) << e;  // the '---' that starts it
}

TEST(DeckHostile, TagsAreAnError) {
  for (const std::string tagged : {"!custom 1.0e-3", "!!str 1.0e-3", "!!float 1.0e-3"}) {
    std::string text = kDeck;
    text.replace(text.find("end_time: 1.0e-3"), 16, "end_time: " + tagged);
    const std::string e = error_of(text);
    EXPECT_NE(e.find("YAML tag"), std::string::npos) << tagged << ": " << e;
    EXPECT_NE(e.find("hostile.yaml:1:"), std::string::npos) << e;
  }
}

TEST(DeckHostile, AliasBombIsRefusedWithoutExpanding) {
  // Billion laughs: 9 levels of 10 aliases each = 1e9 nodes if expanded.
  std::string bomb = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int k = 1; k <= 9; ++k) {
    bomb += "a" + std::to_string(k) + ": &a" + std::to_string(k) + " [";
    for (int j = 0; j < 10; ++j) bomb += (j ? ", *a" : "*a") + std::to_string(k - 1);
    bomb += "]\n";
  }
  const std::string e = error_of(kDeck + bomb);
  EXPECT_NE(e.find("more than 1000000 YAML nodes"), std::string::npos) << e;
}

TEST(DeckHostile, RecursiveAliasIsAnErrorNotACrash) {
  // Found by the fuzzer (tools/fuzz_decks.py): a tree walk followed the alias into itself.
  for (const std::string bad : {"extra: &a [*a]\n", "extra: &m {x: *m}\n"}) {
    const std::string e = error_of(kDeck + bad);
    EXPECT_NE(e.find("recursive alias"), std::string::npos) << bad << ": " << e;
  }
  std::string text = kDeck;
  text.replace(text.find("end_time: 1.0e-3"), 16, "end_time: &c [1, *c]");
  EXPECT_NE(error_of(text).find("recursive alias"), std::string::npos);
}

TEST(DeckHostile, MalformedDocumentsEndQuickly) {
  // "," alone made YAML::LoadAll allocate without end (yaml-cpp issue 1040); now a syntax error.
  for (const std::string& bad : std::vector<std::string>{",", ",\n" + kDeck, kDeck + "---\n,\n"}) {
    const std::string e = error_of(bad);
    EXPECT_NE(e.find("hostile.yaml:"), std::string::npos) << e;
  }
}

TEST(DeckHostile, DuplicateKeyBeforeAPresetMergeIsAnError) {
  const std::string text =
      "simulation: {dimension: plane_strain, end_time: 1.0e-3}\n"
      "grid: {lower: [0, 0], upper: [1, 1], cell_size: 0.125}\n"
      "materials:\n  m:\n    preset: copper_ofhc_jc\n    preset: steel_4340_jc\n"
      "bodies:\n  - {name: b, material: m, shape: {type: box, lower: [0.25, 0.25], upper: [0.5, 0.5]}}\n";
  const std::string e = error_of(text);
  EXPECT_NE(e.find("duplicate key 'preset'"), std::string::npos) << e;
}

TEST(DeckHostile, RowsOfSeparatorsAreErrorsNotBlankLines) {
  ballista::test::TempDir dir{"ballista_hostile"};
  const fs::path table = dir.path / "jet.csv";
  std::ofstream(table) << "1.0e-3, 4.0e-3, 7000, 0\n,,,\n";
  const std::string e = error_of(jet_deck(table.string()));
  EXPECT_NE(e.find("jet.csv:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("separators without numbers"), std::string::npos) << e;
}

TEST(DeckHostile, HugeBadValueIsNotEchoedWhole) {
  std::string text = kDeck;
  const std::string huge(200000, 'z');
  text.replace(text.find("end_time: 1.0e-3"), 16, "end_time: " + huge);
  const std::string e = error_of(text);
  EXPECT_NE(e.find("(200000 characters)"), std::string::npos) << e.substr(0, 300);
  EXPECT_LT(e.size(), 2500u);
  // A long unknown key (yaml-cpp refuses simple keys over 1024 characters itself) is cut too.
  const std::string e2 = error_of(kDeck + std::string(1000, 'k') + ": 1\n");
  EXPECT_NE(e2.find("unknown key 'kkk"), std::string::npos) << e2.substr(0, 300);
  EXPECT_NE(e2.find("(1000 characters)"), std::string::npos) << e2.substr(0, 300);
  EXPECT_LT(e2.size(), 1500u);
}

TEST(DeckHostile, DeviceAndOversizedFilesAreRefused) {
  // /dev/zero as a deck or a table would be read forever (2 GB before failing, issue 11).
  EXPECT_THROW(read_deck("/dev/zero", {}), DeckError);
  try {
    read_deck("/dev/zero", {});
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
  }
  ballista::test::TempDir dir{"ballista_hostile"};
  const fs::path big = dir.path / "big.yaml";
  {
    std::ofstream out(big);
    const std::string line(1 << 20, '#');
    for (int k = 0; k < 65; ++k) out << line << "\n";  // 65 MiB of comment: over the 64 MiB cap
  }
  try {
    read_deck(big.string(), {});
    FAIL() << "a 65 MiB deck was read";
  } catch (const DeckError& e) {
    EXPECT_NE(std::string(e.what()).find("64 MiB"), std::string::npos) << e.what();
  }
}

TEST(DeckHostile, JetTableRowWithInfinityIsNamed) {
  // It used to be taken for a header and dropped ("has no rows").
  ballista::test::TempDir dir{"ballista_hostile"};
  const fs::path table = dir.path / "jet.csv";
  std::ofstream(table) << "1.0e-3, 4.0e-3, inf, 0\n";
  const std::string e = error_of(jet_deck(table.string()));
  EXPECT_NE(e.find("jet.csv:1:"), std::string::npos) << e;
  EXPECT_NE(e.find("expected finite numbers, got 'inf'"), std::string::npos) << e;
}

TEST(DeckHostile, DriveDeckGetsTheSameChecks) {
  const std::string drive =
      "materials:\n  m: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25}\n"
      "drive:\n  legs:\n    - {duration: 1.0e-3, steps: 10, strain: {11: -0.01}}\n";
  EXPECT_NO_THROW(parse_drive_deck(drive, "d.yaml", {}, "."));
  EXPECT_THROW(parse_drive_deck(drive + "---\n{}\n", "d.yaml", {}, "."), DeckError);
  EXPECT_THROW(read_drive_deck("/dev/zero", {}), DeckError);
}

// The cell-count check catches a box in millimetres read as metres (10^9 times the cells). MPM
// allocates the cells, so its limit is 2e9; peridynamics only bounds its points by the box (the
// exploding cylinder's fragments fly 0.3 m on a 0.43 mm lattice), so it may span 1e12.
TEST(DeckHostile, CellCountLimitFollowsWhetherTheSolverAllocatesCells) {
  std::string mpm = kDeck;
  mpm.replace(mpm.find("upper: [1, 1]"), 13, "upper: [1e4, 1e4]");  // 6.4e9 cells
  const std::string e = error_of(mpm);
  EXPECT_NE(e.find("grid.cell_size"), std::string::npos) << e;
  EXPECT_NE(e.find("check that lengths are in metres"), std::string::npos) << e;

  auto pd_deck = [](const std::string& half_width) {
    return "simulation: {solver: peridynamics, dimension: 3d, end_time: 1.0e-6}\n"
           "grid: {lower: [-" + half_width + ", -" + half_width + ", -" + half_width + "], upper: [" +
           half_width + ", " + half_width + ", " + half_width + "], cell_size: 1.0e-3}\n"
           "materials:\n  m: {model: linear_elastic, density: 7850, bulk_modulus: 140e9, shear_modulus: 70e9}\n"
           "bodies:\n  - {name: b, material: m, shape: {type: box, lower: [0, 0, 0], upper: [0.004, 0.004, 0.004]}}\n";
  };
  EXPECT_EQ(error_of(pd_deck("0.8")), "");  // 1600^3 = 4.1e9 lattice cells: a wide box, no mesh
  const std::string huge = error_of(pd_deck("20"));  // 40000^3 = 6.4e13
  EXPECT_NE(huge.find("check that lengths are in metres"), std::string::npos) << huge;
}

}  // namespace test_deck_hostile
