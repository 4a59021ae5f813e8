#include "core/host_cpu.hpp"

#include <fstream>
#include <string>

namespace ballista {

std::string host_cpu() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const auto colon = line.find(':');
    if (colon == std::string::npos) break;
    const auto first = line.find_first_not_of(" \t", colon + 1);
    const auto last = line.find_last_not_of(" \t\r");
    if (first == std::string::npos || last < first) break;
    return line.substr(first, last - first + 1);
  }
  return "unknown";
}

}  // namespace ballista
