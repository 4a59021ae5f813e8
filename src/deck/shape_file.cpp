#include "deck/shape_file.hpp"

#include <filesystem>

namespace ballista {

std::string deck_file(DeckNode& n, const std::string& key, const std::string& what) {
  namespace fs = std::filesystem;
  fs::path path(n.string(key));
  if (path.is_relative()) path = fs::path(n.file()).parent_path() / path;
  path = fs::absolute(path).lexically_normal();
  std::error_code ec;
  if (!fs::exists(path, ec)) n.fail(key, "cannot open the " + what + " file '" + path.string() + "'");
  n.set_resolved(key, YAML::Node(path.string()));
  return path.string();
}

std::string shape_file(DeckNode& s, const std::string& what) { return deck_file(s, "file", what); }

ShapePlacement shape_placement(DeckNode& s) {
  const std::string unit = s.choice("unit", "m", {"m", "cm", "mm", "in"});
  ShapePlacement p;
  p.scale = unit == "mm" ? 1e-3 : unit == "cm" ? 1e-2 : unit == "in" ? 0.0254 : 1.0;
  p.offset = s.vector("offset", Vec3{}, 3);
  return p;
}

ShapeSpec with_solid(DeckNode& s, ShapeSpec sh, std::shared_ptr<const SolidShape> solid) {
  sh.lower = solid->lower();
  sh.upper = solid->upper();
  sh.solid = std::move(solid);
  s.finish();
  return sh;
}

}  // namespace ballista
