#pragma once
// What built this binary, for the provenance of results: `ballista --version` and summary.json
// name it, so a figure in docs/ or a user's report can be traced to the code that made it.

namespace ballista {

/// `git describe --always --dirty` of the source tree at build time ("-dirty": uncommitted
/// changes were built), or "unknown" outside git. Defined in a file generated at every build
/// (cmake/build_info.cmake).
const char* build_commit();

}  // namespace ballista
