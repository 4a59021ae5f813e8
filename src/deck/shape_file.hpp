#pragma once
// What the shapes read from files (`surface`, `mesh`) share: the file, found relative to the
// deck's folder (as any file a deck names: a grid study's record), and its placement (unit and
// offset).
#include <memory>
#include <string>

#include "core/tensor.hpp"
#include "deck/deck_node.hpp"

namespace ballista {

/// The absolute path of the file the map `n` names in `key` (relative to the deck's folder), which
/// must exist; the resolved deck records that path. `what` names the file in errors.
std::string deck_file(DeckNode& n, const std::string& key, const std::string& what);

/// deck_file of the shape map's `file` ("surface", "mesh").
std::string shape_file(DeckNode& s, const std::string& what);

/// How a file's coordinates become metres: x_m = scale x_file + offset.
struct ShapePlacement {
  double scale = 1.0;  ///< metres per unit of the file: `unit` m, cm, mm or in (default m)
  Vec3 offset{};       ///< m, `offset` (default 0)
};
ShapePlacement shape_placement(DeckNode& s);

/// `sh` holding the solid read from its file, its bounds the solid's, after the last key of `s`
/// was read (s.finish()).
ShapeSpec with_solid(DeckNode& s, ShapeSpec sh, std::shared_ptr<const SolidShape> solid);

}  // namespace ballista
