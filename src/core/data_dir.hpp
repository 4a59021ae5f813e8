#pragma once
// Where Ballista's own files are found at run time: the material presets (data/materials.yaml)
// and the Python tools the commands call for figures and reports (tools/*.py). The same binary
// works from its build tree and after `cmake --install` or the Debian package, so the lookup
// starts from the running executable, not from a path compiled in.
#include <string>

namespace ballista {

/// Environment variable naming a directory that holds data/ and tools/ (overrides the search).
inline constexpr const char* kDataDirEnv = "BALLISTA_DATA_DIR";

/// The directory holding data/materials.yaml and tools/, the first of:
/// 1. $BALLISTA_DATA_DIR if set and non-empty (taken as given; a missing file is reported by
///    whoever reads it, with this path in the message);
/// 2. <prefix>/share/ballista, where the executable is <prefix>/bin/<name> (the installed layout);
/// 3. the source tree the binary was built from (BALLISTA_SOURCE_DIR, a compile definition).
std::string data_dir();

/// Which of the three rules above chose data_dir() ("environment", "installed", "source tree"),
/// for messages that say where a file was looked for.
std::string data_dir_origin();

/// The running executable's path (/proc/self/exe), empty if it cannot be read.
std::string executable_path();

}  // namespace ballista
