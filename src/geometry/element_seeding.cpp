#include "geometry/element_seeding.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
#include "geometry/mesh_solid.hpp"
#include "geometry/seeding.hpp"

namespace ballista {

const MeshSolid& element_mesh(const BodySpec& body) {
  const auto* mesh = dynamic_cast<const MeshSolid*>(body.shape.solid.get());
  if (!mesh)
    throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path,
                    "body '" + body.name + "' is seeded at its elements but its shape is not a mesh");
  return *mesh;
}

namespace {

[[noreturn]] void outside(const BodySpec& body, const GridSpec& grid, const char* what, Index count, const Vec3& x) {
  throw DeckError(body.mark.file, body.mark.line, body.mark.column, body.mark.key_path,
                  fmt::format("body '{}': {} {} of its mesh lie outside the grid box [{:g}, {:g}, {:g}] to "
                              "[{:g}, {:g}, {:g}] (e.g. at [{:g}, {:g}, {:g}] m): widen the grid or move the mesh "
                              "(shape.offset)",
                              body.name, count, what, grid.lower[0], grid.lower[1], grid.lower[2], grid.upper[0],
                              grid.upper[1], grid.upper[2], x[0], x[1], x[2]));
}

}  // namespace

Index seed_elements(const BodySpec& body, int body_index, int material_index, const Material& material,
                    const GridSpec& grid, FieldStore& points, std::int64_t& next_id) {
  const TetMesh& m = element_mesh(body).mesh();
  // The nodes sit on the vertices: one on a face of the box (a symmetry plane) is in, to round-off.
  const double tol = 1e-9 * grid.cell_size;
  Index vertices_out = 0;
  Vec3 example;  // the first vertex, then the first centroid, outside
  for (const Vec3& v : element_vertices(body))
    for (int a = 0; a < 3; ++a)
      if (v[a] < grid.lower[a] - tol || v[a] > grid.upper[a] + tol) {
        if (vertices_out++ == 0) example = v;
        break;
      }
  if (vertices_out > 0) outside(body, grid, "vertices", vertices_out, example);

  const Index n = static_cast<Index>(m.tets.size());
  std::vector<Vec3> centroid(m.tets.size());
  Index centroids_out = 0;
  for (std::size_t q = 0; q < m.tets.size(); ++q) {
    const auto& t = m.tets[q];
    centroid[q] = 0.25 * (m.vertices[t[0]] + m.vertices[t[1]] + m.vertices[t[2]] + m.vertices[t[3]]);
    for (int a = 0; a < 3; ++a)
      if (!(centroid[q][a] > grid.lower[a] && centroid[q][a] < grid.upper[a])) {
        if (centroids_out++ == 0) example = centroid[q];
        break;
      }
  }
  if (centroids_out > 0) outside(body, grid, "element centroids", centroids_out, example);

  SeededPoints seeded(points, n);
  for (Index q = 0; q < n; ++q) {
    const auto& t = m.tets[static_cast<std::size_t>(q)];
    const double V = tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]]);
    // (positive: the mesh reader refuses any other element.) The domain the probes and the writer
    // draw (x + F (+-half)): the cube of the element's volume. An element with a face on the
    // body's surface has its centroid a quarter of its height from it, about the cube's half-edge
    // 0.5 V^(1/3): the outermost domains reach the mesh's surface within a few per cent of an
    // element (0.025 h beyond a face of a cube of edge h cut into six; a box about the centroid
    // that holds the element would overshoot by up to h/2).
    const double l = 0.5 * std::cbrt(V);
    seeded.set(q, next_id, body_index, material_index, material.density(), centroid[static_cast<std::size_t>(q)],
               body.velocity, V, Vec3{{l, l, l}});
  }
  return n;
}

std::vector<Vec3> element_vertices(const BodySpec& body) {
  const TetMesh& m = element_mesh(body).mesh();
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& t : m.tets)
    for (int i : t) used[static_cast<std::size_t>(i)] = 1;
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < m.vertices.size(); ++i)
    if (used[i]) out.push_back(m.vertices[i]);
  return out;
}

double mesh_spacing(const BodySpec& body) {
  const TetMesh& m = element_mesh(body).mesh();
  std::vector<double> s;
  s.reserve(m.tets.size());
  for (const auto& t : m.tets)
    s.push_back(std::cbrt(6.0 * tet_volume(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]], m.vertices[t[3]])));
  if (s.empty()) return 0.0;
  auto mid = s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2);
  std::nth_element(s.begin(), mid, s.end());
  return *mid;
}

}  // namespace ballista
