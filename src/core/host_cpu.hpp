#pragma once
// The processor a run ran on, for summary.json: with build_cpu_target() (core/build_info.hpp) it
// says which instructions produced a result's last bits.

#include <string>

namespace ballista {

/// The processor this process runs on (the "model name" of /proc/cpuinfo), or "unknown".
std::string host_cpu();

}  // namespace ballista
