#pragma once
// Watches for points that hold more hydrostatic tension than any solid of their material's moduli
// can (materials/cohesive_limit.hpp): a failed point that keeps its stress (failure.erosion none)
// under a Mie-Grüneisen EOS without eos.min_pressure can be pulled to any tension, and the run
// would otherwise report its answer without a word about it. The run goes on (the state is
// garbage only locally, and stopping would lose the rest of the answer); the first time a material
// is found beyond its limit the run warns, and summary.json "tension" gives, per watched material,
// its limit, the strongest tension seen and the most points beyond the limit at one time.
#include <cstdint>
#include <string>
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"
#include "core/state_archive.hpp"
#include "io/summary_writer.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class TensionWatch {
 public:
  TensionWatch() = default;  ///< watches nothing
  /// Watches every material with a Mie-Grüneisen EOS whose tension cutoff (eos.min_pressure), if
  /// any, lies below its cohesive limit.
  explicit TensionWatch(const Scenario& sc);

  bool empty() const { return watched_.empty(); }

  /// Scans the points at time t (collective: every rank calls it with its own points).
  void scan(const FieldStore& pts, double time, const Communicator& comm);

  /// summary.json "tension": {material: {cohesive_limit, most_tensile_pressure, most_tensile_time,
  /// most_points_beyond, most_points_beyond_time, first_beyond_time}} (times null while there is
  /// nothing to date; docs/output.md).
  JsonValue summary() const;

  void save(StateArchive& a) const;
  /// A checkpoint written before the watch existed restores an empty record.
  void load(const StateArchive& a);

 private:
  struct Watched {
    std::string name;
    double limit = 0.0;      ///< cohesive limit, Pa (negative)
    double bulk = 0.0;       ///< K0, Pa (for the message)
    double most_tensile = 0.0;  ///< the lowest pressure seen, Pa
    double most_tensile_time = -1.0;
    std::int64_t most_beyond = 0;  ///< the most points beyond the limit at one scan
    double most_beyond_time = -1.0;
    double first_beyond_time = -1.0;  ///< < 0: never beyond
  };
  std::vector<Watched> watched_;
  std::vector<int> slot_of_material_;  ///< material index -> index in watched_, -1 if not watched
};

}  // namespace ballista
