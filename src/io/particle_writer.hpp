#pragma once
// Particle output: one HDF5 file per output time (dir/particles_NNNNNN.h5) plus an XDMF 3 index
// (dir/particles.xdmf: created atomically at the first output, then each output's grid is written
// in place over the closing tags, so an output costs the same however long the series) that ParaView opens as a time
// series. Each .h5 holds /time, /step, one dataset per field (N x ncomp, or N for one component;
// real fields as float64, int fields as int64, with a "unit" attribute), /vertex_cells (0..N-1,
// the Polyvertex connectivity) and, with domains, /domain_points and /domain_cells: each
// particle's deformed domain x_p + F_p (±a, ±b, ±c), (a,b,c) = half_size, as a hexahedron (3D)
// or a quadrilateral (2D, c = 0) in VTK/XDMF node order. A second point cloud (the OTM nodes) can
// go into the same files: node_<field> datasets and a grid "nodes" in the output's collection.
#include <string>
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"

namespace ballista {

class ParticleWriter {
 public:
  /// fields: names to write (empty = every field with FieldInfo::output); "x" is always written
  /// (it is the geometry). domains: also write particle domains (needs fields "F" and
  /// "half_size"). dim: 2 (quadrilaterals) or 3 (hexahedra). Creates dir if missing.
  ParticleWriter(std::string dir, std::vector<std::string> fields, bool domains, int dim);

  /// Writes dir/particles_NNNNNN.h5 (NNNNNN = outputs so far) and rewrites dir/particles.xdmf.
  /// `nodes` (optional: the OTM solver's nodes) is written into the same file as datasets
  /// node_<field> (every real field of that store, "x" required) with node_cells, and becomes a
  /// second grid "nodes" beside the particles in the output's spatial collection.
  void write(double time, long step, const FieldStore& points, const FieldStore* nodes = nullptr);
  /// Several MPI ranks: write() becomes collective. Every rank calls it with its own points; one
  /// file per output is written through MPI-IO (parallel HDF5), each rank its rows, in rank order;
  /// rank 0 alone commits it (fsync, rename) and writes the XDMF index. restore() removes and
  /// rewrites files on rank 0 only.
  void set_communicator(const Communicator& comm) { comm_ = comm; }
  /// The bodies' and materials' names in index order: every particle file stores them as the root
  /// attributes `body_names` and `material_names` (JSON arrays of strings).
  void set_names(std::vector<std::string> bodies, std::vector<std::string> materials) {
    body_names_ = std::move(bodies);
    material_names_ = std::move(materials);
  }

  /// Fields whose values are per radian of revolution (axisymmetric) or per metre of thickness
  /// (2D): their "unit" attribute gets `suffix` ("/rad", "/m"), so that the file says what the
  /// numbers are (node fields of the same names too).
  void set_extensive(std::vector<std::string> fields, std::string suffix) {
    extensive_ = std::move(fields);
    extensive_suffix_ = std::move(suffix);
  }

  /// Checkpoint: the output count and the index's text up to its footer.
  struct State {
    int count = 0;
    std::string xdmf_body;  ///< particles.xdmf without the footer ("" before the first output)
  };
  /// The state as it was after output `count` - 1, whose index body ended at `body_end`
  /// (count() and xdmf_body_end() read then): earlier index text is never rewritten.
  State state_at(int count, std::size_t body_end) const;
  std::size_t xdmf_body_end() const { return xdmf_body_end_; }
  /// Restart: the index rewritten from `s` (atomically) and the particle files numbered from
  /// s.count on (written by the interrupted run after its checkpoint) removed; later outputs
  /// continue the numbering.
  void restore(const State& s);

  /// Number of outputs written so far.
  int count() const { return count_; }
  /// Path of the XDMF index.
  std::string xdmf_path() const;
  /// Path of output number `index`.
  std::string h5_path(int index) const;

 private:
  std::string dir_;
  std::vector<std::string> fields_;
  bool domains_;
  int dim_;
  /// Appends one output's XDMF grid to the index (the first output creates it).
  void append_xdmf(const std::string& grid);

  int count_ = 0;                 // outputs written
  Communicator comm_;             // several ranks: collective writes (set_communicator)
  std::vector<std::string> body_names_, material_names_;  // set_names
  std::vector<std::string> extensive_;                    // set_extensive
  std::string extensive_suffix_;
  std::size_t xdmf_body_end_ = 0;  // byte offset of the index's footer (where the next grid goes)
};

}  // namespace ballista
