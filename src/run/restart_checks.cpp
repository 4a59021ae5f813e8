#include "run/restart_checks.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/error.hpp"
#include "deck/deck_changes.hpp"
#include "deck/deck_reader.hpp"

namespace ballista {

std::string layout_signature(const Scenario& sc) {
  std::string s = "solver " + sc.simulation.solver + "\ngrid " +
                  fmt::format("{} {} {} {} {} {} {}", sc.grid.lower[0], sc.grid.lower[1], sc.grid.lower[2],
                              sc.grid.upper[0], sc.grid.upper[1], sc.grid.upper[2], sc.grid.cell_size) +
                  "\n";
  for (const auto& m : sc.materials) s += "material " + m.name + " " + m.model + "\n";
  for (const auto& b : sc.bodies) {
    s += "body " + b.name + " " + b.material + " " + std::to_string(b.particles_per_cell);
    // Only when given: checkpoints written before point_spacing existed keep their signature.
    if (b.point_spacing > 0.0) s += fmt::format(" point_spacing {:.17g}", b.point_spacing);
    s += "\n";
  }
  return s;
}

void check_layout(const StateArchive& a, const Scenario& sc, const std::string& path) {
  if (!a.has("run.layout")) return;
  const std::string want = a.text("run.layout"), have = layout_signature(sc);
  if (want == have) return;
  std::size_t at = 0;
  while (at < want.size() && at < have.size() && want[at] == have[at]) ++at;
  const std::size_t line = want.rfind('\n', at == 0 ? 0 : at - 1);
  const std::size_t from = line == std::string::npos ? 0 : line + 1;
  throw Error("the deck does not match the checkpoint " + path + ": it has '" +
              have.substr(from, have.find('\n', from) - from) + "' where the checkpoint has '" +
              want.substr(from, want.find('\n', from) - from) +
              "' (a restart may change the end time, outputs and guards, not the solver, grid, bodies or material "
              "models)");
}

namespace {

// The stored deck resolved again by this build, without the overrides. Its warnings (a surface
// file read again) were given when the run began and are not repeated. A stored deck this build
// cannot read alone gives the stored text itself: every key it lacks then counts as set by an
// override, and a change of physics is refused, not guessed.
std::string resolved_without_overrides(const std::string& stored, const std::string& file) {
  const spdlog::level::level_enum level = spdlog::get_level();
  spdlog::set_level(spdlog::level::err);
  std::string text = stored;
  try {
    text = parse_deck(stored, file, {}).resolved_yaml;
  } catch (const std::exception&) {
  }
  spdlog::set_level(level);
  return text;
}

}  // namespace

void check_restart_changes(const StateArchive& a, const Scenario& sc, const std::string& path) {
  const std::string stored = a.text("run.deck");
  // The checkpoint's deck resolved by this build without the overrides: it tells a key a later
  // build added, at its default, from one an override sets. Parsed only when a key is new.
  std::string plain = sc.resolved_yaml;
  for (const DeckChange& c : deck_changes(stored, sc.resolved_yaml))
    if (c.before_absent && !restart_may_change(c.key_path)) {
      plain = resolved_without_overrides(stored, sc.file);
      break;
    }
  const std::vector<DeckChange> refused = refused_restart_changes(stored, plain, sc.resolved_yaml);
  if (refused.empty()) return;
  std::string list;
  for (std::size_t k = 0; k < refused.size() && k < 5; ++k)
    list += fmt::format("{}{} ({} -> {})", k ? ", " : "", refused[k].key_path,
                        refused[k].before.empty() ? "not given" : shorten(refused[k].before, 60),
                        refused[k].after.empty() ? "not given" : shorten(refused[k].after, 60));
  if (refused.size() > 5) list += fmt::format(" and {} more", refused.size() - 5);
  throw DeckError(sc.file, 0, 0, refused.front().key_path,
                  "a restart continues the run of checkpoint " + path +
                      " with its physics: it may change the end time, outputs, checkpoints, limits and guards "
                      "(docs/restart.md), but the deck changes " + list +
                      "; run the deck anew to change them");
}

}  // namespace ballista
