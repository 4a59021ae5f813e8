#pragma once
// What built this binary, for the provenance of results: `ballista --version` and summary.json
// name it, so a figure in docs/ or a user's report can be traced to the code that made it.

namespace ballista {

/// `git describe --always --dirty` of the source tree at build time ("-dirty": uncommitted
/// changes were built), or "unknown" outside git. Defined in a file generated at every build
/// (cmake/build_info.cmake).
const char* build_commit();

/// The instruction set the build was compiled for: "native (ARCH)" when the Release build used
/// -march=native (ARCH as the compiler resolved it on the build machine, e.g. znver3), else the
/// -march of CMAKE_CXX_FLAGS (e.g. "x86-64-v3"), else "default" (the compiler's generic x86-64).
/// Two builds of one commit for different processors agree to round-off, not bit for bit.
const char* build_cpu_target();

}  // namespace ballista
