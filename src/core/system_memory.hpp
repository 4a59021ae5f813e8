#pragma once
// What memory the machine has, for refusing a run that cannot fit before it allocates
// (rather than die in a bare std::bad_alloc, as a 210 GB grid would).
#include <cstdint>
#include <string>

namespace ballista {

struct SystemMemory {
  double total_bytes = 0.0;      ///< physical memory (MemTotal)
  double available_bytes = 0.0;  ///< what can be allocated without swapping (MemAvailable), or less
                                 ///< if the process's address space is limited
  double process_limit_bytes = 0.0;  ///< RLIMIT_AS (ulimit -v) if set, else 0
};

/// Reads /proc/meminfo (Linux); falls back to sysconf page counts. Zero when unknown.
SystemMemory system_memory();

/// The memory this process holds now (VmRSS of /proc/self/status), 0 if unknown.
double resident_bytes();

/// "1.23 GB" style figure (decimal units).
std::string format_bytes(double bytes);

/// Throws a DeckError (file, key) if `needed_bytes` exceed the memory available now, with the
/// figure, the breakdown `what` and the machine's memory. A machine whose memory is unknown passes.
void require_memory(double needed_bytes, const std::string& what, const std::string& file, const std::string& key);

}  // namespace ballista
