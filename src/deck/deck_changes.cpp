#include "deck/deck_changes.hpp"

#include <yaml-cpp/yaml.h>

#include <set>

#include "core/error.hpp"

namespace ballista {

namespace {

std::string text_of(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "";
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

void compare(const YAML::Node& a, const YAML::Node& b, const std::string& path, std::vector<DeckChange>& out) {
  const bool a_map = a.IsDefined() && a.IsMap(), b_map = b.IsDefined() && b.IsMap();
  if (a_map && b_map) {
    std::set<std::string> keys;
    for (const auto& kv : a) keys.insert(kv.first.Scalar());
    for (const auto& kv : b) keys.insert(kv.first.Scalar());
    for (const std::string& k : keys) compare(a[k], b[k], path.empty() ? k : path + "." + k, out);
    return;
  }
  const bool a_seq = a.IsDefined() && a.IsSequence(), b_seq = b.IsDefined() && b.IsSequence();
  if (a_seq && b_seq && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i) compare(a[i], b[i], path + "." + std::to_string(i), out);
    return;
  }
  const std::string ta = text_of(a), tb = text_of(b);
  if (ta != tb || a_map != b_map || a_seq != b_seq) out.push_back({path, ta, tb, !a.IsDefined()});
}

YAML::Node parse(const std::string& text, const char* which) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(std::string("cannot compare the ") + which + " deck: " + e.what());
  }
}

}  // namespace

std::vector<DeckChange> deck_changes(const std::string& before_yaml, const std::string& after_yaml) {
  std::vector<DeckChange> out;
  compare(parse(before_yaml, "checkpoint's"), parse(after_yaml, "restart's"), "", out);
  return out;
}

bool restart_may_change(const std::string& key_path) {
  static const std::set<std::string> simulation{"simulation.end_time", "simulation.max_steps", "simulation.step_limit",
                                                "simulation.energy_drift_limit", "simulation.threads"};
  // penetration.layers only chooses which holes the analysis measures (and older decks lack it).
  return simulation.count(key_path) > 0 || key_path.rfind("output.", 0) == 0 || key_path == "output" ||
         key_path.rfind("penetration.layers", 0) == 0;
}

std::vector<DeckChange> refused_restart_changes(const std::string& stored, const std::string& plain,
                                                const std::string& continued) {
  std::vector<DeckChange> refused;
  std::vector<DeckChange> overridden;  // what the overrides changed, computed once if needed
  bool have_overridden = false;
  const auto nested = [](const std::string& a, const std::string& b) {  // a is b or inside it
    return a == b || (a.size() > b.size() && a.compare(0, b.size(), b) == 0 && a[b.size()] == '.');
  };
  // Keys added with a default that changes what some runs do: a checkpoint from before them
  // continues only with the build that wrote it.
  static const std::set<std::string> default_changes_physics{"mpm.distortion_limit"};
  for (DeckChange& c : deck_changes(stored, continued)) {
    if (restart_may_change(c.key_path)) continue;
    if (c.before_absent && !c.after.empty() && default_changes_physics.count(c.key_path) == 0) {
      if (!have_overridden) overridden = deck_changes(plain, continued), have_overridden = true;
      bool set_by_override = false;
      for (const DeckChange& o : overridden)
        set_by_override = set_by_override || nested(o.key_path, c.key_path) || nested(c.key_path, o.key_path);
      if (!set_by_override) continue;
    }
    refused.push_back(std::move(c));
  }
  return refused;
}

}  // namespace ballista
