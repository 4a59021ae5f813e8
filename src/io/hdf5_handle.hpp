#pragma once
// RAII ownership of an HDF5 identifier (file, dataset, dataspace, type, attribute, group), shared
// by the particle writer and the checkpoint file.
#include <hdf5.h>

#include <string>

#include "core/error.hpp"

namespace ballista {

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class H5Id {
 public:
  H5Id(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw Error("HDF5: cannot " + what);
  }
  ~H5Id() {
    if (id_ >= 0) close_(id_);
  }
  H5Id(const H5Id&) = delete;
  H5Id& operator=(const H5Id&) = delete;
  operator hid_t() const { return id_; }
  /// Closes now and reports failure (a file's data are flushed at close).
  void close(const std::string& what) {
    const herr_t rc = close_(id_);
    id_ = -1;
    if (rc < 0) throw Error("HDF5: cannot " + what);
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

/// Dataset creation properties without modification times (HDF5 stores them by default), so
/// that equal states give byte-identical files: a restarted run's outputs compare with `cmp`.
inline hid_t untimed_dataset() {
  static const hid_t dcpl = [] {
    const hid_t p = H5Pcreate(H5P_DATASET_CREATE);
    H5Pset_obj_track_times(p, false);
    return p;
  }();
  return dcpl;
}

/// Silences HDF5's own error printing while alive (the caller reports the failure as an Error
/// with the file's path instead of the library's stack dump), then restores it.
class H5QuietErrors {
 public:
  H5QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~H5QuietErrors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  H5QuietErrors(const H5QuietErrors&) = delete;
  H5QuietErrors& operator=(const H5QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
};

}  // namespace ballista
