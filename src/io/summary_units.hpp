#pragma once
// The SI unit of every number summary.json holds, written beside them as its "units" object so
// that the file says what its numbers mean without the docs (docs/output.md has the meanings).
#include <map>
#include <string>

#include "io/summary_writer.hpp"

namespace ballista {

/// The unit of the number at `path` ("penetration.holes.casing.entrance_diameter";
/// "stages[].start_time" for an array's elements): "m", "kg/m^3", "1" for a count or ratio, ""
/// if the path is not known. `probes.<name>` are not known here (their kinds give them).
std::string summary_unit(const std::string& path);

/// {path: unit} for every number under `root` (arrays' elements as `key[]`), `probe_units` giving
/// those of `probes.<name>`. A number with no known unit is left out of the map.
JsonValue summary_units(const JsonValue& root, const std::map<std::string, std::string>& probe_units);

}  // namespace ballista
