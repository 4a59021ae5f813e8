#include "io/checkpoint_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <regex>

#include <spdlog/spdlog.h>

#include "core/checksum.hpp"
#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/hdf5_handle.hpp"

namespace ballista {

namespace {

constexpr const char* kFormat = "ballista-checkpoint-1";

/// Every dataset carries the checksum of its values (core/checksum.hpp) as attribute "checksum":
/// a damaged checkpoint is found when it is read, not continued from with other physics.
constexpr const char* kChecksum = "checksum";

void write_array(hid_t group, const std::string& name, hid_t mem_type, hid_t file_type, std::size_t n,
                 std::size_t element_bytes, const void* data) {
  const hsize_t dims[1] = {static_cast<hsize_t>(n)};
  H5Id space(H5Screate_simple(1, dims, nullptr), H5Sclose, "create dataspace for '" + name + "'");
  H5Id dset(H5Dcreate2(group, name.c_str(), file_type, space, H5P_DEFAULT, untimed_dataset(), H5P_DEFAULT), H5Dclose,
            "create checkpoint dataset '" + name + "'");
  if (n > 0 && H5Dwrite(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw Error("HDF5: cannot write checkpoint dataset '" + name + "'");
  const std::uint64_t sum = checksum64(data, n * element_bytes);
  H5Id aspace(H5Screate(H5S_SCALAR), H5Sclose, "create attribute dataspace");
  H5Id attr(H5Acreate2(dset, kChecksum, H5T_STD_U64LE, aspace, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
            "create the checksum of '" + name + "'");
  if (H5Awrite(attr, H5T_NATIVE_UINT64, &sum) < 0) throw Error("HDF5: cannot write the checksum of '" + name + "'");
}

/// Names of the members of `group`, in the file's order.
std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info;
  if (H5Gget_info(group, &info) < 0) throw Error("HDF5: cannot list a checkpoint group");
  std::vector<std::string> names;
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t len = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (len < 0) throw Error("HDF5: cannot read a checkpoint dataset name");
    std::string name(static_cast<std::size_t>(len), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size() + 1, H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

/// The values of a dataset, checked against its stored checksum (a checkpoint written before
/// checksums existed has none: `unverified` counts it).
template <class T>
std::vector<T> read_array(hid_t group, const std::string& name, hid_t mem_type, int* unverified = nullptr) {
  H5Id dset(H5Dopen2(group, name.c_str(), H5P_DEFAULT), H5Dclose, "open checkpoint dataset '" + name + "'");
  H5Id space(H5Dget_space(dset), H5Sclose, "get the dataspace of '" + name + "'");
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  if (n < 0) throw Error("HDF5: bad extent of checkpoint dataset '" + name + "'");
  // A damaged size field could ask for any amount: no dataset is larger than the file.
  H5Id file(H5Iget_file_id(dset), H5Fclose, "find the file of '" + name + "'");
  hsize_t file_bytes = 0;
  if (H5Fget_filesize(file, &file_bytes) < 0 || static_cast<hsize_t>(n) * sizeof(T) > file_bytes)
    throw Error("checkpoint dataset '" + name + "' claims " + std::to_string(n) + " values, more than the file holds");
  std::vector<T> v(static_cast<std::size_t>(n));
  if (n > 0 && H5Dread(dset, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) < 0)
    throw Error("HDF5: cannot read checkpoint dataset '" + name + "'");
  if (H5Aexists(dset, kChecksum) <= 0) {
    if (unverified) ++*unverified;
    return v;
  }
  std::uint64_t stored = 0;
  H5Id attr(H5Aopen(dset, kChecksum, H5P_DEFAULT), H5Aclose, "open the checksum of '" + name + "'");
  if (H5Aread(attr, H5T_NATIVE_UINT64, &stored) < 0) throw Error("HDF5: cannot read the checksum of '" + name + "'");
  if (checksum64(v.data(), v.size() * sizeof(T)) != stored)
    throw Error("checkpoint dataset '" + name + "' is damaged (its checksum does not match its values)");
  return v;
}

/// Flushes a closed file's data to the disk, so that the rename publishes complete contents.
void fsync_path(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw Error("cannot reopen '" + path + "' to flush it");
  const int rc = ::fsync(fd);
  ::close(fd);
  if (rc != 0) throw Error("cannot flush '" + path + "' to disk");
}

/// The file opened read-only without file locking (locks fail on some parallel file systems);
/// a negative id if it cannot be opened.
hid_t open_read_only(const std::string& path) {
  H5Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access list");
#if H5_VERSION_GE(1, 10, 7)
  H5Pset_file_locking(fapl, false, true);
#endif
  return H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl);
}

}  // namespace

void write_checkpoint_file(const std::string& path, const StateArchive& archive) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  AtomicPath out(path);
  {
    H5Id fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access list");
#if H5_VERSION_GE(1, 10, 7)
    H5Pset_file_locking(fapl, false, true);  // locks fail on some parallel file systems
#endif
    H5Id h5(H5Fcreate(out.tmp().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), H5Fclose, "create '" + out.tmp() + "'");
    {
      H5Id str(H5Tcopy(H5T_C_S1), H5Tclose, "create string type");
      H5Tset_size(str, std::char_traits<char>::length(kFormat));
      H5Id aspace(H5Screate(H5S_SCALAR), H5Sclose, "create attribute dataspace");
      H5Id attr(H5Acreate2(h5, "format", str, aspace, H5P_DEFAULT, H5P_DEFAULT), H5Aclose, "create 'format'");
      if (H5Awrite(attr, str, kFormat) < 0) throw Error("HDF5: cannot write the checkpoint format");
    }
    {
      H5Id g(H5Gcreate2(h5, "real", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create group 'real'");
      for (const auto& [k, v] : archive.all_reals())
        write_array(g, k, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, v.size(), sizeof(double), v.data());
    }
    {
      H5Id g(H5Gcreate2(h5, "int", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create group 'int'");
      for (const auto& [k, v] : archive.all_ints())
        write_array(g, k, H5T_NATIVE_INT64, H5T_STD_I64LE, v.size(), sizeof(std::int64_t), v.data());
    }
    {
      H5Id g(H5Gcreate2(h5, "text", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose, "create group 'text'");
      for (const auto& [k, v] : archive.all_texts())
        write_array(g, k, H5T_NATIVE_UCHAR, H5T_STD_U8LE, v.size(), 1, v.data());
    }
    h5.close("write '" + out.tmp() + "'");
  }
  fsync_path(out.tmp());
  out.commit();
}

StateArchive read_checkpoint_file(const std::string& path) {
  const H5QuietErrors quiet;
  try {
    H5Id h5(open_read_only(path), H5Fclose, "open '" + path + "'");
    {
      H5Id attr(H5Aopen(h5, "format", H5P_DEFAULT), H5Aclose, "find the checkpoint format of '" + path + "'");
      H5Id type(H5Aget_type(attr), H5Tclose, "read the checkpoint format type");
      std::string fmt(H5Tget_size(type), '\0');
      if (H5Aread(attr, type, fmt.data()) < 0 || fmt != kFormat)
        throw Error("'" + path + "' is not a " + std::string(kFormat) + " file (format '" + fmt + "')");
    }
    StateArchive a;
    int unverified = 0;
    {
      H5Id g(H5Gopen2(h5, "real", H5P_DEFAULT), H5Gclose, "open group 'real'");
      for (const auto& k : member_names(g)) a.put(k, read_array<double>(g, k, H5T_NATIVE_DOUBLE, &unverified));
    }
    {
      H5Id g(H5Gopen2(h5, "int", H5P_DEFAULT), H5Gclose, "open group 'int'");
      for (const auto& k : member_names(g))
        a.put(k, read_array<std::int64_t>(g, k, H5T_NATIVE_INT64, &unverified));
    }
    {
      H5Id g(H5Gopen2(h5, "text", H5P_DEFAULT), H5Gclose, "open group 'text'");
      for (const auto& k : member_names(g)) {
        const auto bytes = read_array<unsigned char>(g, k, H5T_NATIVE_UCHAR, &unverified);
        a.put_text(k, std::string(bytes.begin(), bytes.end()));
      }
    }
    if (unverified > 0)
      spdlog::warn("{}: {} datasets carry no checksum (written by an older Ballista): their integrity is not checked",
                   path, unverified);
    // A checkpoint under another checkpoint's name (files swapped or copied) is not this step.
    const std::string name = std::filesystem::path(path).filename().string();
    static const std::regex kStep("checkpoint_([0-9]{12})\\.h5");
    std::smatch m;
    if (a.has("run.step") && std::regex_match(name, m, kStep) && std::stol(m[1].str()) != a.integer("run.step"))
      throw Error("it holds step " + std::to_string(a.integer("run.step")) + " under the name of step " +
                  std::to_string(std::stol(m[1].str())) + " (files renamed or swapped?)");
    return a;
  } catch (const Error& e) {
    throw Error("cannot read checkpoint '" + path + "': " + e.what());
  }
}

std::string read_checkpoint_text(const std::string& path, const std::string& key) {
  const H5QuietErrors quiet;
  try {
    H5Id h5(open_read_only(path), H5Fclose, "open '" + path + "'");
    H5Id g(H5Gopen2(h5, "text", H5P_DEFAULT), H5Gclose, "open group 'text'");
    const auto bytes = read_array<unsigned char>(g, key, H5T_NATIVE_UCHAR);
    return std::string(bytes.begin(), bytes.end());
  } catch (const Error& e) {
    throw Error("cannot read checkpoint '" + path + "': " + e.what());
  }
}

std::pair<std::string, std::string> newest_checkpoint(const std::string& out_dir) {
  const std::vector<std::string> all = list_checkpoints(out_dir);
  if (all.empty())
    throw Error("'" + out_dir + "' has no checkpoint (" + checkpoint_dir(out_dir) +
                "/checkpoint_*.h5); a run writes them with output.checkpoint_interval or --checkpoint-every-minutes");
  std::string why;
  for (auto it = all.rbegin(); it != all.rend(); ++it) {
    try {
      // The whole file is read and checked, not only its deck: a damaged newer checkpoint gives
      // way to the one before it here, before the run is set up from it.
      const StateArchive a = read_checkpoint_file(*it);
      if (!a.has("run.deck")) throw Error("cannot read checkpoint '" + *it + "': it holds no deck (run.deck)");
      return {*it, a.text("run.deck")};
    } catch (const Error& e) {
      spdlog::warn("skipping {}: {}", *it, e.what());
      why = e.what();
    }
  }
  throw Error("no checkpoint of '" + out_dir + "' can be read: " + why);
}

std::string checkpoint_dir(const std::string& out_dir) {
  return (std::filesystem::path(out_dir) / "checkpoints").string();
}

std::string checkpoint_path(const std::string& out_dir, long step) {
  char name[64];
  std::snprintf(name, sizeof name, "checkpoint_%012ld.h5", step);
  return (std::filesystem::path(checkpoint_dir(out_dir)) / name).string();
}

std::vector<std::string> list_checkpoints(const std::string& out_dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  const fs::path dir = checkpoint_dir(out_dir);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return out;
  static const std::regex kName("checkpoint_[0-9]{12}\\.h5");
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && std::regex_match(entry.path().filename().string(), kName))
      out.push_back(entry.path().string());
  std::sort(out.begin(), out.end());  // zero-padded step numbers: name order is step order
  return out;
}

int remove_checkpoints_after(const std::string& out_dir, const std::string& path) {
  const std::string name = std::filesystem::path(path).filename().string();
  int removed = 0;
  for (const std::string& c : list_checkpoints(out_dir)) {
    std::error_code ec;
    if (std::filesystem::path(c).filename().string() > name && std::filesystem::remove(c, ec)) ++removed;
  }
  return removed;
}

int prune_checkpoints(const std::string& out_dir, int keep) {
  const std::vector<std::string> all = list_checkpoints(out_dir);
  int removed = 0;
  for (std::size_t k = 0; k + static_cast<std::size_t>(keep) < all.size(); ++k) {
    std::error_code ec;
    if (std::filesystem::remove(all[k], ec)) ++removed;
  }
  return removed;
}

}  // namespace ballista
