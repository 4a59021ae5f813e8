#pragma once
// The few numbers a user reads first, printed at the end of `ballista run` from its summary:
// the depth and the hole diameters of a penetration run, the fragments of a fragmentation run,
// with a plain statement when the penetrator is under-resolved.
#include <string>
#include <vector>

#include "io/summary_writer.hpp"

namespace ballista {

/// One line each ("depth into 'rock' = 48.1 mm (cavity 47.9 mm)"), from summary.json's root.
std::vector<std::string> headline_lines(const JsonValue& summary);

}  // namespace ballista
