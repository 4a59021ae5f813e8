#pragma once
// Material points at the elements of a body's volume mesh (`seeding: elements` with `shape:
// {type: mesh}`): the OTM seed's initial discretisation (seed 003 §2, before eq. 2.13: positions,
// densities and volumes "by means of a standard tetrahedral mesh", the nodes at its vertices).
// One point per tetrahedron at its centroid, the one-point quadrature rule of the linear
// tetrahedron (exact for the element's volume and first moments), with the element's volume and
// mass rho V; hexahedra arrive split into six tetrahedra by the mesh reader.
#include <cstdint>
#include <vector>

#include "core/field_store.hpp"
#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class MeshSolid;

/// The mesh of a body whose seeding is `elements` (its shape is a mesh; checked by the deck reader).
const MeshSolid& element_mesh(const BodySpec& body);

/// Appends one point per tetrahedron of `body`'s mesh (3D): at the centroid, volume and reference
/// volume the element's, mass rho0 V, half_size half the edge of the cube of that volume (the
/// domain the probes and the writer draw), F = R = I, the body's velocity. Ids continue from
/// next_id. A centroid outside the grid box, or a vertex beyond it by more than 1e-9 of a cell, is
/// a deck error naming the body. Returns the number of points added.
Index seed_elements(const BodySpec& body, int body_index, int material_index, const Material& material,
                    const GridSpec& grid, FieldStore& points, std::int64_t& next_id);

/// The vertices of `body`'s mesh that its tetrahedra use, in vertex order (OTM's nodes of the body).
std::vector<Vec3> element_vertices(const BodySpec& body);

/// The spacing of `body`'s mesh, m: the median over its tetrahedra of (6 V)^(1/3), the edge of the
/// cube they would fill six at a time (a cube of edge h cut into six tetrahedra gives h; a regular
/// tetrahedron of edge a, 0.89 a), for comparison with the nodal spacing of the LME shape functions.
double mesh_spacing(const BodySpec& body);

}  // namespace ballista
