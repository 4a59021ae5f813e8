#pragma once
// A results folder held by one run. Two runs writing into one folder interleave their particle
// files and leave a malformed particles.xdmf, and a run that cleared a folder by file pattern
// deleted a user's own files (notes.tmp). So a run holds an exclusive lock on its folder for its
// whole life (flock on DIR/.ballista-files: released by the kernel when the process dies, even
// by SIGKILL, so a killed run never leaves a stale lock), and it lists in that same file every
// file it writes there (the manifest). The next run into the folder removes exactly the files
// the manifest lists, with their temporary `.tmp` twins, and nothing else.
#include <string>

namespace ballista {

class RunFolder {
 public:
  enum class Mode {
    NewRun,   ///< clears the previous run's files (its manifest); a folder with other files is refused
    Continue  ///< a restart: keeps what is there and adds to the manifest
  };
  /// Creates `dir` if needed and locks it; throws Error if another run holds it. NewRun: a
  /// folder that is not empty and holds no manifest is refused unless `overwrite`, or unless it
  /// is a results folder of an older Ballista that kept no manifest (resolved.yaml beside
  /// history.csv or summary.json); then the file names Ballista writes are removed.
  RunFolder(const std::string& dir, Mode mode, bool overwrite = false);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  const std::string& dir() const { return dir_; }
  /// Files of an earlier run removed when the folder was taken.
  int removed() const { return removed_; }
  /// Removes every file the manifest lists (with its `.tmp` twin) and starts a new manifest: the
  /// folder is ready for a new run (NewRun does this when it takes the folder). Returns the count.
  int clear();

 private:
  /// Forgets the folder and closes the manifest, which releases the lock.
  void release();

  std::string dir_;
  std::string root_;  ///< absolute, lexically normal form of dir_ (the registry's key)
  std::string manifest_;
  int fd_ = -1;
  int removed_ = 0;
};

/// Name of the manifest and lock file in a results folder.
inline constexpr const char* kRunManifest = ".ballista-files";

/// Records that Ballista is about to write `path`: if it lies in a folder held by a live
/// RunFolder of this process, its path relative to that folder joins the manifest (once).
/// Called by every writer of io (atomic files, history CSVs) and for the figures the Python
/// tools draw; a path outside every held folder is ignored (tests, `ballista drive`).
void note_output_file(const std::string& path);

}  // namespace ballista
