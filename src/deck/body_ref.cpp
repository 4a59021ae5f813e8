#include "deck/body_ref.hpp"

#include <vector>

namespace ballista {

std::string read_body_ref(DeckNode& node, const Scenario& sc, bool required, const std::string& key) {
  const std::string name = required ? node.string(key) : node.string(key, "");
  if (!name.empty() && body_index(sc, name) < 0) {
    std::vector<std::string> names;
    for (const auto& b : sc.bodies) names.push_back(b.name);
    node.fail(key, "unknown body '" + name + "'" + suggest(name, names));
  }
  return name;
}

}  // namespace ballista
