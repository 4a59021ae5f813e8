// The `contact` section (docs/deck.md): velocity fields per body or joined by single_field pairs,
// Coulomb coefficients per field pair, and errors naming the key path and line.
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"

namespace test_deck_contact {

using namespace ballista;

namespace {

const std::string kBase = R"(simulation: {solver: mpm, dimension: plane_strain, end_time: 1.0e-3}
grid: {lower: [0, 0], upper: [0.1, 0.1], cell_size: 0.01}
materials:
  soft: {model: linear_elastic, density: 1000, youngs_modulus: 1.0e6, poisson_ratio: 0.25}
bodies:
  - {name: jet, material: soft, shape: {type: box, lower: [0.04, 0.07], upper: [0.06, 0.09]}}
  - {name: casing, material: soft, shape: {type: box, lower: [0.0, 0.05], upper: [0.1, 0.06]}}
  - {name: rock, material: soft, shape: {type: box, lower: [0.0, 0.0], upper: [0.1, 0.05]}}
)";

DeckError contact_error(const std::string& contact) {
  try {
    parse_deck(kBase + contact, "deck.yaml");
  } catch (const DeckError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a DeckError for " << contact;
  return DeckError("", 0, 0, "", "none");
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(DeckContact, DefaultIsOneVelocityField) {
  const Scenario sc = parse_deck(kBase, "deck.yaml");
  EXPECT_EQ(sc.contact.model, "single_field");
  EXPECT_EQ(sc.contact.fields, 1);
  EXPECT_EQ(sc.contact.body_field, (std::vector<int>{0, 0, 0}));
  EXPECT_EQ(sc.contact.field_names[0], "jet+casing+rock");
}

TEST(DeckContact, FrictionGivesEachBodyAFieldAndSingleFieldPairsJoinThem) {
  const Scenario a = parse_deck(kBase + "contact: {model: friction, friction: 0.2}\n", "deck.yaml");
  EXPECT_EQ(a.contact.fields, 3);
  EXPECT_EQ(a.contact.body_field, (std::vector<int>{0, 1, 2}));
  for (int f = 0; f < 3; ++f)
    for (int g = 0; g < 3; ++g) EXPECT_EQ(a.contact.field_friction[f * 3 + g], 0.2);

  const Scenario b = parse_deck(kBase + "contact:\n  model: friction\n  friction: 0.1\n  pairs:\n"
                                        "    - {bodies: [casing, rock], model: single_field}\n"
                                        "    - {bodies: [jet, rock], friction: 0.5}\n",
                                "deck.yaml");
  EXPECT_EQ(b.contact.fields, 2);
  EXPECT_EQ(b.contact.body_field, (std::vector<int>{0, 1, 1}));
  EXPECT_EQ(b.contact.field_names[1], "casing+rock");
  EXPECT_EQ(b.contact.field_friction[0 * 2 + 1], 0.5);  // the jet-rock pair sets the field pair
  EXPECT_EQ(b.contact.field_friction[1 * 2 + 0], 0.5);

  // Under the default single_field model, only the pairs listed as friction are separated.
  const Scenario c = parse_deck(kBase + "contact: {pairs: [{bodies: [jet, casing]}, {bodies: [jet, rock]}]}\n", "deck.yaml");
  EXPECT_EQ(c.contact.fields, 2);
  EXPECT_EQ(c.contact.body_field, (std::vector<int>{0, 1, 1}));
}

TEST(DeckContact, BadPairsAreDeckErrorsWithTheirKeyPath) {
  DeckError e = contact_error("contact: {model: friction, pairs: [{bodies: [jet, rokc]}]}\n");
  EXPECT_EQ(e.key_path(), "contact.pairs.0.bodies");
  EXPECT_TRUE(contains(e.what(), "unknown body 'rokc'")) << e.what();
  EXPECT_TRUE(contains(e.what(), "rock")) << e.what();  // the suggestion
  EXPECT_EQ(e.line(), 9);

  e = contact_error("contact: {model: friction, pairs: [{bodies: [jet]}]}\n");
  EXPECT_TRUE(contains(e.what(), "two bodies")) << e.what();

  // A friction pair whose bodies a single_field chain has joined cannot slide.
  e = contact_error("contact:\n  model: friction\n  pairs:\n    - {bodies: [jet, casing], model: single_field}\n"
                    "    - {bodies: [casing, rock], model: single_field}\n    - {bodies: [jet, rock], friction: 0.3}\n");
  EXPECT_EQ(e.key_path(), "contact.pairs.2");
  EXPECT_TRUE(contains(e.what(), "share one velocity field (jet+casing+rock")) << e.what();

  // Two pairs that map to the same field pair with different coefficients.
  e = contact_error("contact:\n  model: friction\n  pairs:\n    - {bodies: [casing, rock], model: single_field}\n"
                    "    - {bodies: [jet, casing], friction: 0.3}\n    - {bodies: [jet, rock], friction: 0.4}\n");
  EXPECT_TRUE(contains(e.what(), "contradicts contact.pairs.1")) << e.what();

  e = contact_error("contact: {model: friction, friction: -0.1}\n");
  EXPECT_EQ(e.key_path(), "contact.friction");

  e = contact_error("contact: {model: frictoin}\n");
  EXPECT_EQ(e.key_path(), "contact.model");

  // The gap check is a fraction of the node's volume.
  e = contact_error("contact: {model: friction, min_volume_fraction: 1.5}\n");
  EXPECT_EQ(e.key_path(), "contact.min_volume_fraction");
  EXPECT_EQ(e.line(), 9);  // the contact line, after the deck's eight
}

TEST(DeckContact, TheGapCheckIsOffUnlessGiven) {
  EXPECT_EQ(parse_deck(kBase, "deck.yaml").contact.min_volume_fraction, 0.0);
  const Scenario sc = parse_deck(kBase + "contact: {model: friction, min_volume_fraction: 0.25}\n", "deck.yaml");
  EXPECT_EQ(sc.contact.min_volume_fraction, 0.25);
}

TEST(DeckContact, OtherSolversRefuseSeparateFields) {
  std::string d = kBase;
  d.replace(d.find("solver: mpm"), 11, "solver: peridynamics");
  d.replace(d.find("plane_strain"), 12, "plane_stress");
  try {
    parse_deck(d + "contact: {model: friction}\n", "deck.yaml");
    ADD_FAILURE() << "expected a DeckError";
  } catch (const DeckError& e) {
    EXPECT_EQ(e.key_path(), "contact.model");
    EXPECT_TRUE(contains(e.what(), "separate velocity fields are a grid contact of mpm")) << e.what();
  }
}

}  // namespace test_deck_contact
