#include "driver/drive_deck.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>

#include "deck/deck_node.hpp"
#include "deck/deck_overrides.hpp"
#include "deck/material_reader.hpp"
#include "deck/text_file.hpp"
#include "driver/ftable_csv.hpp"
#include "driver/perturb.hpp"

namespace ballista {

namespace {

const std::vector<std::string> kSections{"materials", "drive"};
const std::vector<std::string> kComponents{"11", "22", "33", "23", "13", "12"};

class DriveReader {
 public:
  DriveReader(std::shared_ptr<DeckContext> ctx, YAML::Node doc, std::string base_dir)
      : ctx_(ctx), root_(ctx, doc), base_dir_(std::move(base_dir)) {}

  DriveDeck read() {
    deck_.file = ctx_->file;
    for (const auto& s : kSections) root_.allow(s);
    root_.finish();
    materials();
    drive();
    deck_.resolved_yaml = root_.resolved_text("drive deck");
    return std::move(deck_);
  }

 private:
  void materials() {
    DeckNode ms = root_.map("materials", true);
    const auto names = ms.entry_names();
    if (names.size() != 1)
      ms.fail("expected exactly one material in a drive deck (name: {model: ..., parameters}), got " +
              std::to_string(names.size()));
    deck_.material = read_material_spec(ms, names[0]);
    ms.finish();
  }

  void drive() {
    DeckNode d = root_.map("drive", true);
    const bool has_table = d.has("table"), has_legs = d.has("legs");
    if (has_table == has_legs)
      d.fail(has_table ? "expected either table or legs in drive, not both"
                       : "expected a deformation program in drive: table (an F-table file or a list of rows) or "
                         "legs (a list of strain/stress legs)");
    DriveProgram& p = deck_.program;
    p.record_every = static_cast<int>(d.integer("record_every", 1, 1, INT_MAX));
    if (has_table) {
      for (const char* k : {"stress_tolerance", "max_iterations"})
        if (d.has(k)) d.fail(k, std::string("'") + k + "' applies to legs (stress control), not to an F-table");
      table(d);
      p.substeps = static_cast<int>(d.integer("substeps", 1, 1, INT_MAX));
      deck_.scale = d.number("scale", 1.0, NumberRange::any());
      deck_.noise = d.number("noise", 0.0, NumberRange::non_negative());
      deck_.seed = static_cast<std::uint64_t>(d.integer("seed", 0, 0, LONG_MAX));
      try {
        p.table = perturb_table(p.table, deck_.scale, deck_.noise, deck_.seed);
      } catch (const Error& e) {
        d.fail(deck_.noise != 0.0 ? "noise" : "scale", e.what());
      }
    } else {
      for (const char* k : {"substeps", "scale", "noise", "seed"})
        if (d.has(k)) d.fail(k, std::string("'") + k + "' applies to an F-table, not to legs");
      legs(d);
      p.stress_tolerance = d.number("stress_tolerance", 1e-10, NumberRange::between(0.0, 1e-2, true, false));
      p.max_iterations = static_cast<int>(d.integer("max_iterations", 50, 1, 10000));
    }
    d.finish();
  }

  // ---- table --------------------------------------------------------------------------------
  void table(DeckNode& d) {
    const YAML::Node v = d.raw("table");
    const std::string key = d.child_path("table");
    if (v.IsScalar()) {
      namespace fs = std::filesystem;
      fs::path path(v.Scalar());
      if (path.is_relative()) path = fs::path(base_dir_) / path;
      deck_.table_file = path.lexically_normal().string();
      if (!fs::exists(path))
        d.fail("table", "cannot open the F-table file '" + v.Scalar() + "' (looked for " + deck_.table_file +
                            "; a relative path is relative to the deck's folder)");
      deck_.program.table = read_ftable_csv(deck_.table_file, key).rows;
      // The resolved deck names the file absolutely, so that it re-runs from any folder.
      d.set_resolved("table", YAML::Node(fs::absolute(path).lexically_normal().string()));
      return;
    }
    const std::string what =
        "an F-table file name or a list of rows [t, F11, F12, F13, F21, F22, F23, F31, F32, F33] "
        "(optionally followed by angle_deg, axis_x, axis_y, axis_z)";
    if (!v.IsSequence()) d.fail("table", "expected " + what);
    YAML::Node out(YAML::NodeType::Sequence);
    std::vector<YAML::Mark> marks;
    for (size_t i = 0; i < v.size(); ++i) {
      const YAML::Node r = v[i];
      const std::string path = key + "." + std::to_string(i);
      if (!r.IsSequence() || (r.size() != 10 && r.size() != 14))
        deck_fail(*ctx_, path, r.Mark(),
                  "expected a row of 10 or 14 numbers (t F11 .. F33 [angle_deg axis_x axis_y axis_z])" +
                      (r.IsSequence() ? ", got " + std::to_string(r.size()) : std::string()));
      double x[14];
      YAML::Node row(YAML::NodeType::Sequence);
      row.SetStyle(YAML::EmitterStyle::Flow);
      for (size_t k = 0; k < r.size(); ++k) {
        if (!scalar_number(r[k], x[k]))
          deck_fail(
              *ctx_, path + "." + std::to_string(k), r[k].Mark(),
              "expected a number, got " + (r[k].IsScalar() ? "'" + r[k].Scalar() + "'" : std::string("a list or map")));
        row.push_back(format_number(x[k]));
      }
      deck_.program.table.push_back(ftable_row(x, r.size()));
      marks.push_back(r.Mark());
      out.push_back(row);
    }
    if (v.size() < 2)
      d.fail("table", "expected at least 2 rows (the initial state and one more), got " + std::to_string(v.size()));
    check_ftable_rows(deck_.program.table, [&](size_t k, const std::string& msg) {
      deck_fail(*ctx_, key + "." + std::to_string(k), marks[k], msg);
    });
    d.set_resolved("table", out);
  }

  // ---- legs ---------------------------------------------------------------------------------
  /// strain: or stress: map of a leg; components given as 11, 22, 33, 23, 13, 12.
  void components(DeckNode& leg, const std::string& key, bool stress, DriveLeg& g, std::array<bool, 6>& given) {
    DeckNode c = leg.map(key, false);
    if (c.present())
      for (auto it = c.yaml().begin(); it != c.yaml().end(); ++it) {
        if (!it->first.IsScalar()) continue;
        const std::string k = it->first.Scalar();
        if (k == "21" || k == "31" || k == "32")
          deck_fail(*ctx_, c.child_path(k), it->first.Mark(),
                    "write the symmetric component " + k + " as " + std::string{k[1], k[0]} +
                        " (components: 11, 22, 33, 23, 13, 12)");
      }
    for (int k = 0; k < 6; ++k) {
      const auto v = c.optional_number(kComponents[k], stress ? NumberRange::any("Pa") : NumberRange::any());
      if (!v) continue;
      if (given[k])
        c.fail(kComponents[k], "component " + kComponents[k] +
                                   " is both strain- and stress-controlled; give it in one of strain or stress");
      given[k] = true;
      g.stress_controlled[k] = stress;
      g.value[k] = *v;
    }
    c.finish();
  }

  void legs(DeckNode& d) {
    DeckNode ls = d.list("legs", true);
    if (ls.size() == 0)
      ls.fail("expected at least one leg {duration: .., steps: .., strain: {11: ..}, stress: {22: 0}}");
    for (size_t i = 0; i < ls.size(); ++i) {
      DeckNode l = ls.element(i);
      DriveLeg g;
      g.duration = l.number("duration", NumberRange::positive("s"));
      g.steps = static_cast<int>(l.integer("steps", 1, 100000000));
      std::array<bool, 6> given{};
      components(l, "strain", false, g, given);
      components(l, "stress", true, g, given);
      l.finish();
      deck_.program.legs.push_back(g);
    }
  }

  std::shared_ptr<DeckContext> ctx_;
  DeckNode root_;
  std::string base_dir_;
  DriveDeck deck_;
};

}  // namespace

DriveDeck parse_drive_deck(const std::string& yaml_text, const std::string& file_name,
                           const std::vector<std::string>& overrides, const std::string& base_dir) {
  DeckDocument d = open_deck_document(yaml_text, file_name, overrides, "drive deck", "materials, drive");
  DriveReader reader(d.ctx, d.root, base_dir);
  return reader.read();
}

DriveDeck read_drive_deck(const std::string& path, const std::vector<std::string>& overrides) {
  const std::string text = read_input_file(path, "", "the deck file");
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return parse_drive_deck(text, path, overrides, dir.empty() ? "." : dir);
}

}  // namespace ballista
