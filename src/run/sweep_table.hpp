#pragma once
// The parameter study of `ballista sweep` (docs/sweep.md), independent of how runs are executed:
// the --vary axes and their Cartesian product, the flattening of a run's summary.json into
// scalar cells, and the table of all runs written as sweep.csv and sweep.json.
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/summary_writer.hpp"

namespace ballista {

/// One --vary option: a deck key path and the values it takes, each a YAML value text.
struct SweepAxis {
  std::string key;                  ///< dotted deck key path, as for `run --set`
  std::vector<std::string> values;  ///< value texts in the order given
};

/// Parses "key.path=v1,v2,...". Values are split at commas outside brackets, braces and quotes,
/// so flow lists stay whole: "bodies.0.velocity=[0,-100,0],[0,-200,0]" has two values. Throws
/// Error naming the option if there is no '=', the key is empty, a value is empty or a bracket
/// is unbalanced.
SweepAxis parse_vary(const std::string& text);

/// Parses every --vary option; also rejects the same key given twice.
std::vector<SweepAxis> parse_vary_options(const std::vector<std::string>& texts);

/// The Cartesian product of the axes' values, one vector (a value per axis) per run, the last
/// axis varying fastest (nested loops in the order the options were given). No axes: one run
/// with no varied values.
std::vector<std::vector<std::string>> sweep_product(const std::vector<SweepAxis>& axes);

/// A table cell: its text as written in CSV and the JSON kind it has in sweep.json.
struct SweepCell {
  enum class Kind { Number, Bool, String };
  std::string text;
  Kind kind = Kind::String;
};

/// Classifies a value text: a finite number (whole text) -> Number, true/false -> Bool, else
/// String.
SweepCell sweep_cell(const std::string& text);

/// Flattens a parsed summary.json into (column, cell) pairs: nested keys joined by dots
/// (probes.max_eqps, energy.kinetic), array elements by index (tracked_particles.0), JSON null
/// skipped (it is an empty cell), quoted strings kept as strings. Keys listed in `skip` (top level)
/// are left out.
std::vector<std::pair<std::string, SweepCell>> flatten_summary(const YAML::Node& summary,
                                                               const std::vector<std::string>& skip = {});

/// One run of the sweep as it appears in the table.
struct SweepRow {
  int index = 0;                                           ///< run number k (folder run_<k>)
  std::vector<std::string> values;                         ///< one per axis
  std::string status;                                      ///< "completed" or "failed"
  std::string error;                                       ///< why it failed (empty when completed)
  std::vector<std::pair<std::string, SweepCell>> scalars;  ///< the flattened summary.json
};

/// All runs of a sweep. Columns: run, one per axis (named by its key path), status, error, then
/// the union of the runs' summary columns in order of first appearance (a run without a column
/// has an empty cell, null in JSON).
class SweepTable {
 public:
  explicit SweepTable(std::vector<SweepAxis> axes) : axes_(std::move(axes)) {}
  void add(SweepRow row) { rows_.push_back(std::move(row)); }

  const std::vector<SweepAxis>& axes() const { return axes_; }
  const std::vector<SweepRow>& rows() const { return rows_; }
  /// The summary columns (union over rows, first-appearance order).
  std::vector<std::string> summary_columns() const;
  /// Every column of sweep.csv, in order.
  std::vector<std::string> columns() const;
  /// Number of rows whose status is not "completed".
  int failed() const;

  /// CSV text (RFC 4180: a field with a comma, quote or line break is quoted, quotes doubled).
  std::string csv() const;
  /// {"axes": [{key, values}], "columns": [...], "runs": [{column: value}]}; numbers stay numbers.
  JsonValue json() const;
  /// Writes out_dir/sweep.csv and out_dir/sweep.json atomically.
  void write(const std::filesystem::path& out_dir) const;

 private:
  std::vector<SweepAxis> axes_;
  std::vector<SweepRow> rows_;
};

}  // namespace ballista
