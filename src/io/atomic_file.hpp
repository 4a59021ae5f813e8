#pragma once
// Atomic file output: each file is written to NAME.tmp in the same directory and renamed over
// NAME once complete, so a run killed mid-write leaves the previous complete NAME (or none),
// never a truncated one. A stale NAME.tmp may remain after a kill; it is overwritten next time.
#include <string>

namespace ballista {

/// Temporary path used while `path` is being written: path + ".tmp" (same directory).
std::string tmp_path_for(const std::string& path);

/// Writes `contents` to path.tmp, fsyncs it and renames it over `path`; throws Error on failure.
void write_file_atomic(const std::string& path, const std::string& contents);

/// Renames the completely written `tmp` over `final_path` (atomic on POSIX); throws Error.
/// Does not fsync (protects against a killed process, not against an OS crash).
void commit_atomic(const std::string& tmp, const std::string& final_path);

/// Guard for writers that need a file name (HDF5): write to tmp(), then commit(). If commit() is
/// never reached (an exception), the destructor removes the temporary file.
class AtomicPath {
 public:
  explicit AtomicPath(std::string final_path);
  ~AtomicPath();
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;

  const std::string& tmp() const { return tmp_; }
  const std::string& final_path() const { return final_; }
  /// Renames tmp() over final_path(); throws Error.
  void commit();

 private:
  std::string final_;
  std::string tmp_;
  bool committed_ = false;
};

}  // namespace ballista
