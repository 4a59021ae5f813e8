// The decks shipped with Ballista (examples/*.yaml and the complete example of docs/deck.md) must
// parse, and their resolved form must resolve to itself.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"

namespace test_deck_examples {

using namespace ballista;

namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The resolved YAML without its first (comment) line, which names the source file.
std::string body_of(const std::string& resolved) { return resolved.substr(resolved.find('\n') + 1); }

}  // namespace

TEST(DeckExamples, DocsCompleteExampleParses) {
  const std::string doc = read_text(std::filesystem::path(BALLISTA_SOURCE_DIR) / "docs" / "deck.md");
  const size_t heading = doc.find("## Complete example");
  ASSERT_NE(heading, std::string::npos);
  const size_t start = doc.find("```yaml\n", heading);
  ASSERT_NE(start, std::string::npos);
  const size_t end = doc.find("```", start + 8);
  ASSERT_NE(end, std::string::npos);
  const std::string deck = doc.substr(start + 8, end - start - 8);
  Scenario s;
  try {
    s = parse_deck(deck, "docs/deck.md");
  } catch (const Error& e) {
    FAIL() << e.what();
  }
  EXPECT_EQ(s.solver_params.choices.at("shape_function"), "gimp");
  EXPECT_EQ(s.grid.faces[4], FaceBC::Symmetry);
  EXPECT_EQ(s.bodies.at(0).velocity[1], -227.0);
  EXPECT_EQ(s.loads.at(1).curve.t.size(), 3u);
  EXPECT_EQ(s.probes.size(), 4u);
  EXPECT_EQ(s.simulation.energy_drift_limit, 0.05);
  const Scenario again = parse_deck(s.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(body_of(again.resolved_yaml), body_of(s.resolved_yaml));
}

TEST(DeckExamples, ExampleDecksParseAndResolveToThemselves) {
  const auto dir = std::filesystem::path(BALLISTA_SOURCE_DIR) / "examples";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no examples directory";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    // drive_*.yaml are decks of `ballista drive` (tests/unit/driver/test_drive_deck.cpp).
    if (entry.path().filename().string().rfind("drive_", 0) == 0) continue;
    ++count;
    Scenario s;
    try {
      s = read_deck(entry.path().string());
    } catch (const Error& e) {
      ADD_FAILURE() << entry.path() << ": " << e.what();
      continue;
    }
    EXPECT_FALSE(s.bodies.empty()) << entry.path();
    const Scenario again = parse_deck(s.resolved_yaml, "resolved.yaml");
    EXPECT_EQ(body_of(again.resolved_yaml), body_of(s.resolved_yaml)) << entry.path();
  }
  EXPECT_GT(count, 0);
}

}  // namespace test_deck_examples
