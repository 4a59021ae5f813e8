// The run-deck key output.track.ids (particle histories for replay through `ballista drive`).
#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"

namespace test_track_deck {

using namespace ballista;

namespace {

const std::string kDeck =
    "simulation: {dimension: plane_strain, end_time: 1.0e-3}\n"
    "grid: {lower: [0, 0], upper: [0.0625, 0.03125], cell_size: 0.00390625}\n"
    "materials:\n"
    "  putty: {model: linear_elastic, density: 1000, youngs_modulus: 100, poisson_ratio: 0.25}\n"
    "bodies:\n"
    "  - {name: left, material: putty, shape: {type: box, lower: [0.004, 0.012], upper: [0.01, 0.02]}}\n";

std::string error_of(const std::string& output) {
  try {
    parse_deck(kDeck + output, "t.yaml");
  } catch (const DeckError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(TrackDeck, IdsAreReadAndResolved) {
  const Scenario s = parse_deck(kDeck + "output: {track: {ids: [3, 0, 17]}}\n", "t.yaml");
  EXPECT_EQ(s.output.track, (std::vector<std::int64_t>{3, 0, 17}));
  EXPECT_EQ(s.output.track_mark.line, 7);
  EXPECT_NE(s.resolved_yaml.find("ids: [3, 0, 17]"), std::string::npos) << s.resolved_yaml;
  const Scenario again = parse_deck(s.resolved_yaml, "r.yaml");
  EXPECT_EQ(again.output.track, s.output.track);
  EXPECT_TRUE(parse_deck(kDeck, "t.yaml").output.track.empty());
  EXPECT_EQ(parse_deck(kDeck, "t.yaml", {"output.track.ids=[5]"}).output.track, (std::vector<std::int64_t>{5}));
}

TEST(TrackDeck, BadIds) {
  EXPECT_NE(error_of("output: {track: {ids: [1, -2]}}\n")
                .find("t.yaml:7:27: 'output.track.ids.1': expected a particle id (an integer >= 0), got '-2'"),
            std::string::npos)
      << error_of("output: {track: {ids: [1, -2]}}\n");
  EXPECT_NE(error_of("output: {track: {ids: [1.5]}}\n").find("got '1.5'"), std::string::npos);
  EXPECT_NE(error_of("output: {track: {ids: [4, 4]}}\n").find("particle id 4 is listed twice"), std::string::npos);
  EXPECT_NE(error_of("output: {track: {ids: 4}}\n").find("expected a list of particle ids"), std::string::npos);
  EXPECT_NE(error_of("output: {track: {id: [4]}}\n").find("did you mean 'ids'?"), std::string::npos);
}

}  // namespace test_track_deck
