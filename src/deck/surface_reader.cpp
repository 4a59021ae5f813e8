#include "deck/surface_reader.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <tuple>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "deck/shape_file.hpp"
#include "deck/text_file.hpp"
#include "geometry/surface_solid.hpp"

namespace ballista {

namespace {

namespace fs = std::filesystem;

/// Every triangle of the scene's meshes, placed by the node transforms, in the file's units.
void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, std::vector<Vec3>& corners) {
  const aiMatrix4x4 m = parent * node->mTransformation;
  for (unsigned k = 0; k < node->mNumMeshes; ++k) {
    const aiMesh* mesh = scene->mMeshes[node->mMeshes[k]];
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines of an OBJ: no surface
      for (unsigned c = 0; c < 3; ++c) {
        const aiVector3D p = m * mesh->mVertices[face.mIndices[c]];
        corners.push_back({{p.x, p.y, p.z}});
      }
    }
  }
  for (unsigned k = 0; k < node->mNumChildren; ++k) collect(scene, node->mChildren[k], m, corners);
}

/// Triangles from corner triples; corners closer than 1e-9 of the surface's size are one vertex
/// (an STL file repeats every vertex in each of its triangles).
TriangleSurface weld(const std::vector<Vec3>& corners) {
  Vec3 lo = corners[0], hi = corners[0];
  for (const Vec3& p : corners)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  const double size = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
  const double q = 1e-9 * size;
  std::map<std::tuple<long long, long long, long long>, int> index;
  TriangleSurface s;
  for (std::size_t k = 0; k < corners.size(); k += 3) {
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      const Vec3& p = corners[k + c];
      const auto key = std::make_tuple(std::llround((p[0] - lo[0]) / q), std::llround((p[1] - lo[1]) / q),
                                       std::llround((p[2] - lo[2]) / q));
      const auto [it, added] = index.try_emplace(key, static_cast<int>(s.vertices.size()));
      if (added) s.vertices.push_back(p);
      t[c] = it->second;
    }
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2]) s.triangles.push_back(t);  // drop slivers of zero area
  }
  return s;
}

}  // namespace

ShapeSpec read_surface_shape(DeckNode& s) {
  ShapeSpec sh;
  sh.type = "surface";
  const fs::path path = shape_file(s, "surface");
  const std::string ext = path.extension().string();
  if (ext != ".stl" && ext != ".STL" && ext != ".obj" && ext != ".OBJ")
    s.fail("file", "expected a surface file ending in .stl or .obj, got '" + path.filename().string() + "'");
  const std::string bytes = read_input_file(path.string(), s.child_path("file"), "the surface file");
  const ShapePlacement place = shape_placement(s);
  sh.file = path.string();

  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), aiProcess_Triangulate,
                                                     ext.substr(1).c_str());
  if (!scene || !scene->mRootNode)
    s.fail("file", "cannot read the surface file '" + path.string() + "': " + importer.GetErrorString());
  std::vector<Vec3> corners;
  collect(scene, scene->mRootNode, aiMatrix4x4(), corners);
  if (corners.empty()) s.fail("file", "the surface file '" + path.string() + "' holds no triangle");
  for (Vec3& p : corners) p = place.scale * p + place.offset;
  TriangleSurface surface = weld(corners);
  if (surface.triangles.empty())
    s.fail("file", "the surface file '" + path.string() + "' holds only triangles of zero area");

  // A body is the inside of a closed surface. A few open edges (a facet lost in export) are
  // outvoted by the three rays of the inside test; more mean the surface is not a solid's boundary.
  const SurfaceClosure c = surface_closure(surface);
  const Vec3& at = c.open_edge_at;
  if (c.open_edges > 0 && 100 * c.open_edges > c.edges)
    s.fail("file", fmt::format("the surface in '{}' does not close: {} of its {} edges border one triangle only "
                               "(one at ({:.6g}, {:.6g}, {:.6g}) m); a body needs a closed surface (close the "
                               "holes in the CAD tool, or export the solid rather than a face set)",
                               path.string(), c.open_edges, c.edges, at[0], at[1], at[2]));
  if (c.open_edges > 0)
    spdlog::warn("the surface in '{}' has {} open edges of {} (one at ({:.6g}, {:.6g}, {:.6g}) m): a small hole; "
                 "the points near it are placed by a majority of three rays",
                 path.string(), c.open_edges, c.edges, at[0], at[1], at[2]);
  return with_solid(s, std::move(sh), std::make_shared<SurfaceSolid>(std::move(surface)));
}

}  // namespace ballista
