#pragma once
// A body's shape read from a volume mesh: `shape: {type: mesh, file: part.exo, block: casing,
// unit: mm, offset: [x, y, z]}` (Exodus II, read with Debian's libexodusii). The mesh says where
// the body's material is; the body is then seeded with its own lattice (geometry/mesh_solid.hpp).
#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Reads the `shape` map `s` of type mesh (3D decks only): the file relative to the deck's folder;
/// `block`, the name of one element block (default: every block; an unnamed block is called
/// block_<id>); `unit` (m, cm, mm, in; default m); `offset` (m, added after scaling). Tetrahedra
/// (TETRA, TET4, 4 nodes) and hexahedra (HEX, HEX8, 8 nodes; split into 6 tetrahedra) are read;
/// a file that cannot be read, a 2D mesh, another element type, an unknown block or an element
/// of zero or negative volume is an error at the key that causes it.
ShapeSpec read_mesh_shape(DeckNode& s);

}  // namespace ballista
