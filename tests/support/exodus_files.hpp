#pragma once
// Exodus II volume meshes written for the tests of mesh shapes (deck/mesh_reader.hpp): nodes and
// named element blocks, written with libexodusii as a mesh generator would.
#include <exodusII.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/tensor.hpp"

namespace ballista::test {

struct ExodusBlock {
  std::string name;
  std::string type;                ///< "HEX8", "TETRA", "WEDGE", ...
  int nodes_per_element = 8;
  std::vector<int> connectivity;   ///< 1-based node numbers
};

/// Writes an Exodus II file of `dim` dimensions (z ignored for 2) with the given nodes and blocks;
/// netcdf4: in the HDF5-based netCDF-4 format (what newer meshers write) instead of netCDF classic.
inline void write_exodus(const std::string& path, const std::vector<Vec3>& nodes, const std::vector<ExodusBlock>& blocks,
                         int dim = 3, bool netcdf4 = false) {
  int cpu_word = sizeof(double), io_word = sizeof(double);
  const int id = ex_create(path.c_str(), EX_CLOBBER | (netcdf4 ? EX_NETCDF4 : 0), &cpu_word, &io_word);
  if (id < 0) throw std::runtime_error("ex_create failed for " + path);
  int elements = 0;
  for (const auto& b : blocks) elements += static_cast<int>(b.connectivity.size()) / b.nodes_per_element;
  ex_put_init(id, "ballista test mesh", dim, static_cast<int>(nodes.size()), elements,
              static_cast<int>(blocks.size()), 0, 0);
  std::vector<double> x, y, z;
  for (const Vec3& p : nodes) {
    x.push_back(p[0]);
    y.push_back(p[1]);
    z.push_back(p[2]);
  }
  ex_put_coord(id, x.data(), y.data(), dim == 3 ? z.data() : nullptr);
  std::vector<std::vector<char>> names;
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const auto& blk = blocks[b];
    const int bid = static_cast<int>(b) + 1;
    ex_put_elem_block(id, bid, blk.type.c_str(), static_cast<int>(blk.connectivity.size()) / blk.nodes_per_element,
                      blk.nodes_per_element, 0);
    ex_put_elem_conn(id, bid, blk.connectivity.data());
    names.emplace_back(blk.name.begin(), blk.name.end());
    names.back().push_back('\0');
  }
  std::vector<char*> name_ptrs;
  for (auto& n : names) name_ptrs.push_back(n.data());
  ex_put_names(id, EX_ELEM_BLOCK, name_ptrs.data());
  ex_close(id);
}

/// The nodes of an nx x ny x nz lattice of hexahedra over the box [lo, hi] (node (i, j, k) at
/// index 1 + i + (nx+1) (j + (ny+1) k)) and the hexahedra's connectivity in Exodus order.
inline void box_hexes(const Vec3& lo, const Vec3& hi, int nx, int ny, int nz, std::vector<Vec3>& nodes,
                      std::vector<int>& hexes) {
  const int base = static_cast<int>(nodes.size());
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        nodes.push_back({{lo[0] + (hi[0] - lo[0]) * i / nx, lo[1] + (hi[1] - lo[1]) * j / ny,
                          lo[2] + (hi[2] - lo[2]) * k / nz}});
  auto n = [&](int i, int j, int k) { return base + 1 + i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        hexes.insert(hexes.end(), {n(i, j, k), n(i + 1, j, k), n(i + 1, j + 1, k), n(i, j + 1, k), n(i, j, k + 1),
                                   n(i + 1, j, k + 1), n(i + 1, j + 1, k + 1), n(i, j + 1, k + 1)});
}

/// A hexahedron's five tetrahedra (a corner cut off at each of four corners, and the middle one):
/// another split than the reader's six, so that a tetrahedral box is not the reader's own split.
inline std::vector<int> five_tets(const std::array<int, 8>& h) {
  return {h[0], h[1], h[3], h[4], h[1], h[2], h[3], h[6], h[1], h[4], h[5], h[6],
          h[3], h[4], h[6], h[7], h[1], h[3], h[4], h[6]};
}

}  // namespace ballista::test
