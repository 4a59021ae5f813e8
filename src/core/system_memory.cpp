#include "core/system_memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace ballista {

SystemMemory system_memory() {
  SystemMemory m;
  std::ifstream in("/proc/meminfo");
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    std::string key;
    double kib = 0.0;
    s >> key >> kib;  // "MemTotal:  24576000 kB"
    if (key == "MemTotal:") m.total_bytes = kib * 1024.0;
    if (key == "MemAvailable:") m.available_bytes = kib * 1024.0;
  }
  if (m.total_bytes <= 0.0) {
    const long pages = sysconf(_SC_PHYS_PAGES), avail = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && size > 0) m.total_bytes = static_cast<double>(pages) * size;
    if (avail > 0 && size > 0) m.available_bytes = static_cast<double>(avail) * size;
  }
  if (m.available_bytes <= 0.0) m.available_bytes = m.total_bytes;
  // A process address-space limit (ulimit -v) caps what this process can allocate, whatever the
  // machine has: take what is left of it (the limit minus the current virtual size).
  rlimit lim{};
  if (getrlimit(RLIMIT_AS, &lim) == 0 && lim.rlim_cur != RLIM_INFINITY) {
    double vm = 0.0;
    std::ifstream st("/proc/self/status");
    std::string l;
    while (std::getline(st, l))
      if (l.rfind("VmSize:", 0) == 0) vm = std::stod(l.substr(7)) * 1024.0;
    const double left = static_cast<double>(lim.rlim_cur) - vm;
    m.process_limit_bytes = static_cast<double>(lim.rlim_cur);
    m.available_bytes = std::min(m.available_bytes, std::max(left, 0.0));
  }
  return m;
}

double resident_bytes() {
  std::ifstream st("/proc/self/status");
  std::string l;
  while (std::getline(st, l))
    if (l.rfind("VmRSS:", 0) == 0) return std::stod(l.substr(6)) * 1024.0;  // "VmRSS:  12345 kB"
  return 0.0;
}

std::string format_bytes(double bytes) {
  if (bytes >= 1e12) return fmt::format("{:.3g} TB", bytes / 1e12);
  if (bytes >= 1e9) return fmt::format("{:.3g} GB", bytes / 1e9);
  if (bytes >= 1e6) return fmt::format("{:.3g} MB", bytes / 1e6);
  return fmt::format("{:.3g} kB", bytes / 1e3);
}

void require_memory(double needed_bytes, const std::string& what, const std::string& file, const std::string& key) {
  const SystemMemory m = system_memory();
  if (m.available_bytes <= 0.0 || needed_bytes <= m.available_bytes) return;
  throw DeckError(file, 0, 0, key,
                  fmt::format("the run needs about {} ({}) but this machine has {} available ({} in all{}); "
                              "coarsen the resolution or shrink the grid box",
                              format_bytes(needed_bytes), what, format_bytes(m.available_bytes),
                              format_bytes(m.total_bytes),
                              m.process_limit_bytes > 0.0
                                  ? "; the process is limited to " + format_bytes(m.process_limit_bytes) +
                                        " (ulimit -v)"
                                  : std::string()));
}

}  // namespace ballista
