#include "deck/mesh_reader.hpp"

#include <exodusII.h>
#include <netcdf.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "deck/shape_file.hpp"
#include "geometry/mesh_solid.hpp"

namespace ballista {

namespace {

namespace fs = std::filesystem;

std::string upper_case(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

/// An open Exodus file, closed when it goes out of scope.
class ExodusFile {
 public:
  explicit ExodusFile(const std::string& path) {
    int cpu_word = sizeof(double), io_word = 0;
    float version = 0;
    ex_opts(0);  // no messages on stderr, no abort: every failure is reported by the caller
    id_ = ex_open(path.c_str(), EX_READ, &cpu_word, &io_word, &version);
  }
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
  }
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;
  int id() const { return id_; }

 private:
  int id_ = -1;
};

struct Block {
  int id = 0;
  std::string name, type;
  int elements = 0, nodes_per_element = 0;
  std::vector<int> connectivity;  ///< 1-based node numbers, nodes_per_element per element
};

}  // namespace

ShapeSpec read_mesh_shape(DeckNode& s) {
  ShapeSpec sh;
  sh.type = "mesh";
  const fs::path path = shape_file(s, "mesh");
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) s.fail("file", "the mesh file '" + path.string() + "' is not a regular file");
  const bool has_block = s.has("block");
  const std::string wanted = has_block ? s.string("block") : std::string();
  const ShapePlacement place = shape_placement(s);
  sh.file = path.string();

  const ExodusFile exo(path.string());
  const std::string file = "the mesh file '" + path.string() + "'";
  if (exo.id() < 0) s.fail("file", "cannot read " + file + " as Exodus II");
  char title[MAX_LINE_LENGTH + 1] = {};
  int dim = 0, nodes = 0, elements = 0, nblocks = 0, node_sets = 0, side_sets = 0;
  if (ex_get_init(exo.id(), title, &dim, &nodes, &elements, &nblocks, &node_sets, &side_sets) < 0)
    s.fail("file", "cannot read the header of " + file);
  if (dim != 3) s.fail("file", fmt::format("{} is a {}D mesh; a mesh shape fills a 3D body", file, dim));
  if (nodes <= 0 || nblocks <= 0) s.fail("file", file + " holds no nodes or no element blocks");
  std::vector<double> x(static_cast<std::size_t>(nodes)), y(x.size()), z(x.size());
  if (ex_get_coord(exo.id(), x.data(), y.data(), z.data()) < 0) s.fail("file", "cannot read the nodes of " + file);
  // libexodusii 6.02 (Debian 12) returns zeros for x when its variable `coordx` has netCDF id 0,
  // which writers other than the Exodus library produce (scipy's netCDF writer puts the longest
  // variables first): read it through netCDF then (the Exodus id is the netCDF id).
  int coordx_id = -1;
  if (nc_inq_varid(exo.id(), "coordx", &coordx_id) == NC_NOERR && coordx_id == 0 &&
      nc_get_var_double(exo.id(), coordx_id, x.data()) != NC_NOERR)
    s.fail("file", "cannot read the x coordinates of " + file);

  std::vector<int> ids(static_cast<std::size_t>(nblocks));
  if (ex_get_elem_blk_ids(exo.id(), ids.data()) < 0) s.fail("file", "cannot read the element blocks of " + file);
  std::vector<std::vector<char>> name_store(ids.size(), std::vector<char>(MAX_STR_LENGTH + 1, '\0'));
  std::vector<char*> names;
  for (auto& n : name_store) names.push_back(n.data());
  const bool named = ex_get_names(exo.id(), EX_ELEM_BLOCK, names.data()) >= 0;
  std::vector<Block> blocks;
  std::string all_names;
  for (std::size_t b = 0; b < ids.size(); ++b) {
    Block blk;
    blk.id = ids[b];
    blk.name = named && names[b][0] ? std::string(names[b]) : "block_" + std::to_string(blk.id);
    all_names += (all_names.empty() ? "" : ", ") + blk.name;
    blocks.push_back(std::move(blk));
  }
  if (has_block) {
    const auto it = std::find_if(blocks.begin(), blocks.end(), [&](const Block& b) { return b.name == wanted; });
    if (it == blocks.end())
      s.fail("block", fmt::format("{} has no element block '{}'; its blocks: {}", file, wanted, all_names));
    blocks = {*it};
  }

  TetMesh mesh;
  mesh.vertices.resize(static_cast<std::size_t>(nodes));
  for (std::size_t n = 0; n < mesh.vertices.size(); ++n)
    mesh.vertices[n] = place.scale * Vec3{{x[n], y[n], z[n]}} + place.offset;
  for (Block& blk : blocks) {
    char type[MAX_STR_LENGTH + 1] = {};
    int attributes = 0;
    if (ex_get_elem_block(exo.id(), blk.id, type, &blk.elements, &blk.nodes_per_element, &attributes) < 0)
      s.fail("file", fmt::format("cannot read element block '{}' of {}", blk.name, file));
    blk.type = upper_case(type);
    const bool tet = blk.type.rfind("TET", 0) == 0 && blk.nodes_per_element == 4;
    const bool hex = blk.type.rfind("HEX", 0) == 0 && blk.nodes_per_element == 8;
    if (!tet && !hex)
      s.fail(has_block ? "block" : "file",
             fmt::format("element block '{}' of {} holds {} elements of {} nodes; a mesh shape reads tetrahedra "
                         "(TETRA, 4 nodes) and hexahedra (HEX, 8 nodes): export linear elements",
                         blk.name, file, type, blk.nodes_per_element));
    if (blk.elements <= 0) continue;
    blk.connectivity.resize(static_cast<std::size_t>(blk.elements) * static_cast<std::size_t>(blk.nodes_per_element));
    if (ex_get_elem_conn(exo.id(), blk.id, blk.connectivity.data()) < 0)
      s.fail("file", fmt::format("cannot read the connectivity of element block '{}' of {}", blk.name, file));
    for (int e = 0; e < blk.elements; ++e) {
      const int* c = blk.connectivity.data() + static_cast<std::ptrdiff_t>(e) * blk.nodes_per_element;
      for (int k = 0; k < blk.nodes_per_element; ++k)
        if (c[k] < 1 || c[k] > nodes)
          s.fail("file", fmt::format("element {} of block '{}' of {} names node {} (the file has {} nodes)", e + 1,
                                     blk.name, file, c[k], nodes));
      std::vector<std::array<int, 4>> tets;
      if (tet) {
        tets.push_back({c[0] - 1, c[1] - 1, c[2] - 1, c[3] - 1});
      } else {
        std::array<int, 8> h{};
        for (int k = 0; k < 8; ++k) h[static_cast<std::size_t>(k)] = c[k] - 1;
        for (const auto& t : hex_tets(h)) tets.push_back(t);
      }
      for (const auto& t : tets) {
        const auto& v = mesh.vertices;
        const double vol = tet_volume(v[t[0]], v[t[1]], v[t[2]], v[t[3]]);
        if (!(vol > 0.0))
          s.fail("file", fmt::format("element {} of block '{}' of {} is inverted or flat (a tetrahedron of volume "
                                     "{:.3g} m^3 at node ({:.6g}, {:.6g}, {:.6g}) m): the mesh is not valid",
                                     e + 1, blk.name, file, vol, v[t[0]][0], v[t[0]][1], v[t[0]][2]));
        mesh.tets.push_back(t);
      }
    }
  }
  if (mesh.tets.empty()) s.fail(has_block ? "block" : "file", file + ": the selected blocks hold no elements");
  auto solid = std::make_shared<MeshSolid>(std::move(mesh));
  const std::string which =
      has_block ? "block '" + wanted + "'" : fmt::format("{} block{}", blocks.size(), blocks.size() == 1 ? "" : "s");
  spdlog::info("mesh shape: {} ({}), {:.6g} m^3", path.filename().string(), which, solid->volume());
  return with_solid(s, std::move(sh), std::move(solid));
}

}  // namespace ballista
