#pragma once
// A body's shape read from a surface file: `shape: {type: surface, file: part.stl, unit: mm,
// offset: [x, y, z]}` (STL, ASCII or binary, and OBJ, read with Assimp). The triangles are
// scaled to metres, welded at shared vertices and checked to close before they bound a body.
#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Reads the `shape` map `s` of type surface (3D decks only): the file relative to the deck's
/// folder, `unit` (m, cm, mm, in; default m), `offset` (m, added after scaling). A file that cannot
/// be read, holds no triangle or whose surface does not close is an error at `shape.file`; a
/// surface with a few open edges (under 1 % of its edges) is taken with a warning.
ShapeSpec read_surface_shape(DeckNode& s);

}  // namespace ballista
