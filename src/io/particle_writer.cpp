// Only MPI's C API is used (hdf5.h of the parallel build includes mpi.h).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "io/particle_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

#include <hdf5.h>
#include <mpi.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "core/point_fields.hpp"
#include "core/tensor.hpp"
#include "io/atomic_file.hpp"
#include "io/hdf5_handle.hpp"

namespace ballista {

namespace {

/// Several ranks: this rank's rows [first, first + rows) of every dataset written collectively
/// (transfer list `dxpl`); rows == 0 and dxpl == H5P_DEFAULT: the serial write of everything.
struct RowSlice {
  hsize_t first = 0;
  hsize_t rows = 0;
  hid_t dxpl = H5P_DEFAULT;
  bool root = true;  ///< writes the scalar datasets
};

/// A fixed-length string attribute `name` = `text` on an object (every rank calls it alike).
void write_text_attribute(hid_t obj, const char* name, const std::string& text, const std::string& of) {
  H5Id str(H5Tcopy(H5T_C_S1), H5Tclose, "create string type");
  if (H5Tset_size(str, std::max<std::size_t>(text.size(), 1)) < 0) throw Error("HDF5: cannot size string type");
  H5Id aspace(H5Screate(H5S_SCALAR), H5Sclose, "create attribute dataspace");
  H5Id attr(H5Acreate2(obj, name, str, aspace, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
            std::string("create attribute '") + name + "' of " + of);
  const std::string value = text.empty() ? std::string(1, '\0') : text;
  if (H5Awrite(attr, str, value.data()) < 0) throw Error(std::string("HDF5: cannot write ") + name + " of " + of);
}

/// Writes a dataset of the given shape (empty dims = scalar) and an optional "unit" attribute. With
/// a collective slice, `data` holds this rank's rows of dims[0] (every rank calls it alike).
void write_dataset(hid_t file, const std::string& name, hid_t mem_type, hid_t file_type,
                   const std::vector<hsize_t>& dims, const void* data, const std::string& unit,
                   const RowSlice& slice = {}) {
  H5Id space(dims.empty() ? H5Screate(H5S_SCALAR)
                          : H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
             H5Sclose, "create dataspace for '" + name + "'");
  H5Id dset(H5Dcreate2(file, name.c_str(), file_type, space, H5P_DEFAULT, untimed_dataset(), H5P_DEFAULT),
            H5Dclose, "create dataset '" + name + "'");
  hsize_t total = 1;
  for (hsize_t d : dims) total *= d;
  if (slice.dxpl == H5P_DEFAULT) {
    if (total > 0 && H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
      throw Error("HDF5: cannot write dataset '" + name + "'");
  } else {
    // Collective: every rank takes part, each selecting its rows (or nothing).
    H5Id fspace(H5Dget_space(dset), H5Sclose, "dataspace of '" + name + "'");
    std::vector<hsize_t> count = dims, start(dims.size(), 0);
    hsize_t rows = 0;
    if (dims.empty()) {
      rows = slice.root ? 1 : 0;
      if (!slice.root) H5Sselect_none(fspace);
    } else {
      rows = slice.rows;
      start[0] = slice.first;
      count[0] = slice.rows;
      if (rows > 0)
        H5Sselect_hyperslab(fspace, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
      else
        H5Sselect_none(fspace);
    }
    std::vector<hsize_t> mdims = dims.empty() ? std::vector<hsize_t>{1} : count;
    if (mdims[0] == 0) mdims[0] = 1;  // a dataspace of zero rows: select none of one
    H5Id mspace(H5Screate_simple(static_cast<int>(mdims.size()), mdims.data(), nullptr), H5Sclose,
                "memory dataspace of '" + name + "'");
    if (rows == 0) H5Sselect_none(mspace);
    const double dummy = 0.0;
    if (H5Dwrite(dset, mem_type, mspace, fspace, slice.dxpl, rows > 0 ? data : &dummy) < 0)
      throw Error("HDF5: cannot write dataset '" + name + "' (collective)");
  }
  if (!unit.empty()) write_text_attribute(dset, "unit", unit, "'" + name + "'");
}

/// "[\"a\", \"b\"]": names as a JSON array (json.loads in Python), escaped for JSON.
std::string json_names(const std::vector<std::string>& names) {
  std::string out = "[";
  for (std::size_t k = 0; k < names.size(); ++k) {
    out += k ? ", \"" : "\"";
    for (char c : names[k]) {
      if (c == '"' || c == '\\') out += '\\';
      out += c;
    }
    out += '"';
  }
  return out + "]";
}

/// Escapes text for an XML attribute value or element content.
std::string xml_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

/// Round-trip representation of a double.
std::string num(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// XDMF DataItem referencing dataset `name` of `file` with the given rows x cols (cols 1 = 1-D).
std::string data_item(const std::string& file, const std::string& name, Index rows, int cols,
                      bool is_int, const std::string& indent) {
  std::string dims = std::to_string(rows);
  if (cols != 1) dims.append(1, ' ').append(std::to_string(cols));
  return indent + "<DataItem Dimensions=\"" + dims + "\" NumberType=\"" + (is_int ? "Int" : "Float") +
         "\" Precision=\"8\" Format=\"HDF\">" + xml_escape(file) + ":/" + xml_escape(name) +
         "</DataItem>\n";
}

/// XDMF attribute type for a component count.
const char* attribute_type(int ncomp) {
  switch (ncomp) {
    case 1: return "Scalar";
    case 3: return "Vector";
    case 9: return "Tensor";
    default: return "Matrix";
  }
}

/// Attributes for every written field, centred on nodes (particles) or cells (domains); each
/// field's dataset is `prefix` + its name.
std::string attributes(const std::string& file, const std::vector<const FieldInfo*>& fields, Index n,
                       const char* center, const std::string& indent, const std::string& prefix = "") {
  std::string s;
  for (const FieldInfo* f : fields) {
    s += indent + "<Attribute Name=\"" + xml_escape(f->name) + "\" AttributeType=\"" +
         attribute_type(f->ncomp) + "\" Center=\"" + center + "\">\n";
    s += data_item(file, prefix + f->name, n, f->ncomp, f->type == FieldType::Int, indent + "  ");
    s += indent + "</Attribute>\n";
  }
  return s;
}

/// One Polyvertex grid of n points: connectivity dataset `cells`, geometry dataset `x`, then the
/// given attributes.
std::string polyvertex_grid(const std::string& name, const std::string& time, const std::string& file,
                            const std::string& cells, const std::string& x, Index n, const std::string& attrs,
                            const std::string& in) {
  std::string g;
  g += in + "<Grid Name=\"" + name + "\" GridType=\"Uniform\">\n";
  g += in + "  <Time Value=\"" + time + "\"/>\n";
  g += in + "  <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" + std::to_string(n) +
       "\" NodesPerElement=\"1\">\n";
  g += data_item(file, cells, n, 1, true, in + "    ");
  g += in + "  </Topology>\n";
  g += in + "  <Geometry GeometryType=\"XYZ\">\n";
  g += data_item(file, x, n, 3, false, in + "    ");
  g += in + "  </Geometry>\n";
  g += attrs;
  g += in + "</Grid>\n";
  return g;
}

const char* const kReserved[] = {"time", "step", "vertex_cells", "domain_points", "domain_cells"};

/// The point fields an output writes: the requested names (a name listed twice once), or every
/// field marked for output when none are requested.
std::vector<const FieldInfo*> selected_fields(const FieldStore& points, const std::vector<std::string>& requested) {
  std::vector<const FieldInfo*> sel;
  if (requested.empty()) {
    for (const FieldInfo& f : points.fields())
      if (f.output) sel.push_back(&f);
  } else {
    for (const std::string& name : requested) {
      if (!points.has(name)) throw Error("output field '" + name + "' does not exist");
      bool dup = false;  // a field listed twice is written once
      for (const FieldInfo* f : sel) dup = dup || f->name == name;
      if (!dup) sel.push_back(&points.info(name));
    }
  }
  return sel;
}

/// Refuses an output the files cannot hold: geometry "x" that is not real with 3 components,
/// domains without F and half_size, a field name that is no dataset name or is reserved.
void check_output_fields(const FieldStore& points, const FieldStore* nodes, bool domains,
                         const std::vector<const FieldInfo*>& sel) {
  if (!points.has_shape(kPosition))
    throw Error("particle output needs a real field 'x' with 3 components");
  if (nodes && !nodes->has_shape(kPosition))
    throw Error("node output needs a real field 'x' with 3 components");
  if (domains && !(points.has(kDeformationGradient) && points.has(kHalfSize)))
    throw Error("particle domain output needs fields 'F' (Mat3) and 'half_size' (Vec3)");
  for (const FieldInfo* f : sel) {
    if (f->name.empty() || f->name.find('/') != std::string::npos)
      throw Error("field name '" + f->name + "' cannot be an HDF5 dataset name");
    for (const char* r : kReserved)
      if (f->name == r) throw Error("field name '" + f->name + "' is reserved in particle output");
  }
}

/// This rank's place in the output's rows.
struct GlobalRows {
  Index n = 0;      ///< rows of every point dataset
  Index first = 0;  ///< this rank's first row
};

/// Several ranks: the global row count and this rank's first row (rank order), gathered from
/// every rank's count (collective); one rank: its own rows from 0.
GlobalRows global_rows(const Communicator& comm, Index local) {
  GlobalRows g{local, 0};
  if (comm.distributed()) {
    std::vector<int> counts;
    const std::vector<std::int64_t> all = comm.all_gather({static_cast<std::int64_t>(local)}, counts);
    g.n = 0;
    for (int r = 0; r < comm.size(); ++r) {
      if (r < comm.rank()) g.first += all[r];
      g.n += all[r];
    }
  }
  return g;
}

/// Several ranks: the file opened through MPI-IO on `comm` and every dataset written collectively,
/// this rank its `local` rows from `first`.
RowSlice collective_access(hid_t fapl, hid_t dxpl, const Communicator& comm, Index first, Index local) {
  MPI_Comm c;
  const std::uintptr_t h = comm.native_handle();
  std::memcpy(&c, &h, sizeof c);
  if (H5Pset_fapl_mpio(fapl, c, MPI_INFO_NULL) < 0) throw Error("HDF5: cannot set MPI-IO file access");
  if (H5Pset_dxpl_mpio(dxpl, H5FD_MPIO_COLLECTIVE) < 0) throw Error("HDF5: cannot set collective transfers");
  return RowSlice{static_cast<hsize_t>(first), static_cast<hsize_t>(local), dxpl, comm.rank() == 0};
}

/// A field's "unit" attribute: its unit, with the suffix of an extensive field of a 2D or
/// axisymmetric run ("kg/rad", "J/m"; ParticleWriter::set_extensive).
struct UnitOf {
  const std::vector<std::string>& extensive;
  const std::string& suffix;
  std::string operator()(const FieldInfo& f) const {
    const bool per = !suffix.empty() && std::find(extensive.begin(), extensive.end(), f.name) != extensive.end();
    return per ? f.unit + suffix : f.unit;
  }
};

/// The selected point fields, the geometry "x" (always: it places the points) and the explicit
/// Polyvertex connectivity, each an n-row dataset.
void write_point_datasets(hid_t h5, const FieldStore& points, const std::vector<const FieldInfo*>& sel, Index n,
                          Index first, const RowSlice& rows, const UnitOf& unit_of) {
  bool x_selected = false;
  for (const FieldInfo* f : sel) x_selected = x_selected || f->name == "x";
  std::vector<const FieldInfo*> datasets = sel;
  if (!x_selected) datasets.push_back(&points.info("x"));
  for (const FieldInfo* f : datasets) {
    std::vector<hsize_t> dims{static_cast<hsize_t>(n)};
    if (f->ncomp != 1) dims.push_back(static_cast<hsize_t>(f->ncomp));
    if (f->type == FieldType::Real)
      write_dataset(h5, f->name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, dims, points.real(f->name), unit_of(*f), rows);
    else
      write_dataset(h5, f->name, H5T_NATIVE_INT64, H5T_STD_I64LE, dims, points.ints(f->name), unit_of(*f), rows);
  }

  // Polyvertex connectivity: readers differ on implicit connectivity, so it is explicit.
  const Index local = points.size();
  std::vector<std::int64_t> verts(static_cast<size_t>(local));
  for (Index p = 0; p < local; ++p) verts[p] = first + p;
  write_dataset(h5, "vertex_cells", H5T_NATIVE_INT64, H5T_STD_I64LE, {static_cast<hsize_t>(n)},
                verts.data(), "", rows);
}

/// Corners per particle domain: a hexahedron in 3D, a quadrilateral in 2D.
int domain_corners(int dim) { return dim == 3 ? 8 : 4; }

/// Each particle's deformed domain x_p + F_p (±half_size) as cell corners (domain_points) and
/// cells (domain_cells), so that a reader draws the domains, not just the points.
void write_domain_datasets(hid_t h5, const FieldStore& points, int dim, Index n, Index first, const RowSlice& rows) {
  const Index local = points.size();
  const int nc = domain_corners(dim);
  const Vec3* x = points.view<Vec3>("x");
  const Mat3* F = points.view<Mat3>("F");
  const Vec3* h = points.view<Vec3>("half_size");
  // Corner sign patterns in VTK/XDMF order: bottom face counter-clockwise, then top face.
  static const int s3[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                               {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  static const int s2[4][3] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const int(*sign)[3] = dim == 3 ? s3 : s2;
  std::vector<Vec3> corners(static_cast<size_t>(local * nc));
  std::vector<std::int64_t> cells(static_cast<size_t>(local * nc));
  for_each(0, local, [&](Index p) {
    for (int k = 0; k < nc; ++k) {
      const Vec3 r{{sign[k][0] * h[p][0], sign[k][1] * h[p][1], sign[k][2] * h[p][2]}};
      corners[p * nc + k] = x[p] + F[p] * r;
      cells[p * nc + k] = (first + p) * nc + k;
    }
  });
  RowSlice corner_rows = rows;  // nc corner rows per particle
  corner_rows.first *= static_cast<hsize_t>(nc);
  corner_rows.rows *= static_cast<hsize_t>(nc);
  write_dataset(h5, "domain_points", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE,
                {static_cast<hsize_t>(n * nc), 3}, corners.data(), points.info("x").unit, corner_rows);
  write_dataset(h5, "domain_cells", H5T_NATIVE_INT64, H5T_STD_I64LE,
                {static_cast<hsize_t>(n), static_cast<hsize_t>(nc)}, cells.data(), "", rows);
}

/// The second point cloud (OTM nodes): every real field, prefixed node_, with its own vertices.
/// Several ranks hold every node alike (OTM): rank 0 writes them (`rows` says which rank it is).
void write_node_datasets(hid_t h5, const FieldStore& nodes, const UnitOf& unit_of, RowSlice rows) {
  const Index nn = nodes.size();
  if (rows.dxpl != H5P_DEFAULT) {
    rows.first = 0;
    rows.rows = rows.root ? static_cast<hsize_t>(nn) : 0;
  }
  for (const FieldInfo& f : nodes.fields()) {
    if (f.type != FieldType::Real) continue;
    std::vector<hsize_t> dims{static_cast<hsize_t>(nn)};
    if (f.ncomp != 1) dims.push_back(static_cast<hsize_t>(f.ncomp));
    write_dataset(h5, "node_" + f.name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, dims, nodes.real(f.name), unit_of(f), rows);
  }
  std::vector<std::int64_t> nv(static_cast<size_t>(nn));
  for (Index a = 0; a < nn; ++a) nv[a] = a;
  write_dataset(h5, "node_cells", H5T_NATIVE_INT64, H5T_STD_I64LE, {static_cast<hsize_t>(nn)}, nv.data(), "", rows);
}

/// The XDMF grid(s) of output `index` in `file`: particles (Polyvertex), with domains the deformed
/// cells, with nodes a second Polyvertex grid; several grids go into a spatial collection.
std::string output_grid(double time, int index, const std::string& file, Index n,
                        const std::vector<const FieldInfo*>& sel, bool domains, int dim, const FieldStore* nodes) {
  const int nc = domain_corners(dim);
  const std::string t = num(time);
  const std::string name = "output_" + std::to_string(index);
  std::string g;
  std::string in = "      ";
  const bool collection = domains || nodes;
  if (collection) {
    g += in + "<Grid Name=\"" + name + "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
    g += in + "  <Time Value=\"" + t + "\"/>\n";
    in += "  ";
  }
  g += polyvertex_grid("particles", t, file, "vertex_cells", "x", n,
                       attributes(file, sel, n, "Node", in + "  "), in);
  if (domains) {
    g += in + "<Grid Name=\"domains\" GridType=\"Uniform\">\n";
    g += in + "  <Time Value=\"" + t + "\"/>\n";
    g += in + "  <Topology TopologyType=\"" + (dim == 3 ? "Hexahedron" : "Quadrilateral") +
         "\" NumberOfElements=\"" + std::to_string(n) + "\">\n";
    g += data_item(file, "domain_cells", n, nc, true, in + "    ");
    g += in + "  </Topology>\n";
    g += in + "  <Geometry GeometryType=\"XYZ\">\n";
    g += data_item(file, "domain_points", n * nc, 3, false, in + "    ");
    g += in + "  </Geometry>\n";
    g += attributes(file, sel, n, "Cell", in + "  ");
    g += in + "</Grid>\n";
  }
  if (nodes) {
    std::vector<const FieldInfo*> node_fields;
    for (const FieldInfo& f : nodes->fields())
      if (f.type == FieldType::Real && f.name != "x") node_fields.push_back(&f);
    const Index nn = nodes->size();
    g += polyvertex_grid("nodes", t, file, "node_cells", "node_x", nn,
                         attributes(file, node_fields, nn, "Node", in + "  ", "node_"), in);
  }
  if (collection) g += "      </Grid>\n";
  return g;
}

}  // namespace

ParticleWriter::ParticleWriter(std::string dir, std::vector<std::string> fields, bool domains, int dim)
    : dir_(std::move(dir)), fields_(std::move(fields)), domains_(domains), dim_(dim) {
  if (dim_ != 2 && dim_ != 3) throw Error("ParticleWriter: dim must be 2 or 3, got " + std::to_string(dim_));
  if (dir_.empty()) dir_.assign(1, '.');
  std::error_code ec;
  std::filesystem::create_directories(dir_, ec);
  if (ec) throw Error("cannot create output directory '" + dir_ + "': " + ec.message());
}

std::string ParticleWriter::xdmf_path() const { return dir_ + "/particles.xdmf"; }

std::string ParticleWriter::h5_path(int index) const {
  char name[32];
  std::snprintf(name, sizeof name, "particles_%06d.h5", index);
  return dir_ + "/" + name;
}

void ParticleWriter::write(double time, long step, const FieldStore& points, const FieldStore* nodes) {
  // Fields to write: the requested ones (or every output field); "x" is the geometry.
  const std::vector<const FieldInfo*> sel = selected_fields(points, fields_);
  check_output_fields(points, nodes, domains_, sel);

  const Index local = points.size();
  const bool parallel = comm_.distributed();
  const bool root = comm_.rank() == 0;
  const auto [n, first] = global_rows(comm_, local);
  const int index = count();
  const std::string path = h5_path(index);
  const std::string file = std::filesystem::path(path).filename().string();  // relative to the xdmf

  {
    // Rank 0 alone owns the temporary file's fate (an AtomicPath of another rank would unlink it).
    std::optional<AtomicPath> out;
    if (root) out.emplace(path);
    const std::string tmp = path + ".tmp";
    {
      H5Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access list");
#if H5_VERSION_GE(1, 10, 7)
      H5Pset_file_locking(fapl, false, true);  // locks fail on some parallel file systems
#endif
      H5Id dxpl(H5Pcreate(H5P_DATASET_XFER), H5Pclose, "create transfer list");
      RowSlice rows;
      if (parallel) rows = collective_access(fapl, dxpl, comm_, first, local);
      H5Id h5(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose, "create '" + tmp + "'");
      write_dataset(h5, "time", H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, {}, &time, "s", rows);
      const std::int64_t step64 = step;
      write_dataset(h5, "step", H5T_NATIVE_INT64, H5T_STD_I64LE, {}, &step64, "", rows);
      // The names behind the `body` and `material` indices, so that a file read alone says them.
      if (!body_names_.empty()) write_text_attribute(h5, "body_names", json_names(body_names_), "the file");
      if (!material_names_.empty())
        write_text_attribute(h5, "material_names", json_names(material_names_), "the file");
      const UnitOf unit_of{extensive_, extensive_suffix_};
      write_point_datasets(h5, points, sel, n, first, rows, unit_of);
      if (domains_) write_domain_datasets(h5, points, dim_, n, first, rows);
      if (nodes) write_node_datasets(h5, *nodes, unit_of, rows);
      h5.close("close '" + tmp + "'");  // collective: every rank's rows are in the file
    }
    if (root) out->commit();
  }

  const std::string g = output_grid(time, index, file, n, sel, domains_, dim_, nodes);
  if (root) append_xdmf(g);
  ++count_;
}

namespace {
const std::string kXdmfFooter =
    "    </Grid>\n"
    "  </Domain>\n"
    "</Xdmf>\n";
}  // namespace

ParticleWriter::State ParticleWriter::state_at(int count, std::size_t body_end) const {
  State s;
  s.count = count;
  if (count == 0) return s;
  std::ifstream in(xdmf_path(), std::ios::binary);
  std::string text(body_end, '\0');
  if (!in.read(text.data(), static_cast<std::streamsize>(text.size())))
    throw Error("'" + xdmf_path() + "' is shorter than this run wrote it");
  s.xdmf_body = std::move(text);
  return s;
}

void ParticleWriter::restore(const State& s) {
  namespace fs = std::filesystem;
  if (comm_.rank() != 0) {  // several ranks: rank 0 alone touches the files
    count_ = s.count;
    xdmf_body_end_ = s.xdmf_body.size();
    return;
  }
  // Outputs the interrupted run wrote after the checkpoint: numbered s.count and on.
  for (int k = s.count;; ++k) {
    std::error_code ec;
    if (!fs::remove(h5_path(k), ec)) break;
  }
  count_ = s.count;
  xdmf_body_end_ = s.xdmf_body.size();
  std::error_code ec;
  if (count_ == 0)
    fs::remove(xdmf_path(), ec);
  else
    write_file_atomic(xdmf_path(), s.xdmf_body + kXdmfFooter);
}

void ParticleWriter::append_xdmf(const std::string& grid) {
  const std::string& kFooter = kXdmfFooter;
  if (count_ == 0) {
    // The first output writes the whole index atomically (a new run never shows an old index).
    const std::string head =
        "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
        "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n"
        "  <Domain>\n"
        "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    write_file_atomic(xdmf_path(), head + grid + kFooter);
    xdmf_body_end_ = head.size() + grid.size();
    return;
  }
  // Later outputs overwrite the footer with the new grid and the footer, in place: the cost of an
  // output does not grow with the series (rewriting the whole index, 2,299 outputs would each
  // rewrite up to 18.9 MB with fsync). One write() of a few kB; a kill inside it could leave the
  // index without its footer, while every particle file stays complete.
  const std::string tail = grid + kFooter;
  const int fd = ::open(xdmf_path().c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) throw Error("cannot open '" + xdmf_path() + "' to append output " + std::to_string(count_));
  const char* p = tail.data();
  size_t left = tail.size();
  off_t at = static_cast<off_t>(xdmf_body_end_);
  while (left > 0) {
    const ssize_t n = ::pwrite(fd, p, left, at);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      ::close(fd);
      throw Error("cannot append to '" + xdmf_path() + "'");
    }
    p += n;
    at += n;
    left -= static_cast<size_t>(n);
  }
  if (::close(fd) != 0) throw Error("cannot close '" + xdmf_path() + "'");
  xdmf_body_end_ += grid.size();
}

}  // namespace ballista
