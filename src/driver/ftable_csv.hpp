#pragma once
// F-table files (CATALOGUE §A; thesis §4.2.1): the deformation program of a single-element test,
// and what `ballista run` writes for a tracked particle (output.track, tracks/particle_<id>.csv).
//
// Format: one row per line, `t F11 F12 F13 F21 F22 F23 F31 F32 F33 [angle_deg axis_x axis_y axis_z]`
// (F row-major; the optional rotation of angle_deg degrees about the axis accumulates over the row
// ending at t). Cells are separated by commas and/or blanks. Blank lines and lines starting with
// '#' are ignored. An optional first line names the columns exactly as above
// (t,F11,...,F33[,angle_deg,axis_x,axis_y,axis_z]); every row must then have that many cells,
// otherwise 10 or 14. Numbers are read to full precision (a history written with 17 significant
// digits, or shortest round-trip, replays the exact doubles).
#include <string>
#include <vector>

#include "driver/point_driver.hpp"

namespace ballista {

struct FTableFile {
  std::vector<FTableRow> rows;
  std::vector<int> lines;  ///< 1-based line of each row, for messages
};

/// Column names of an F-table file (with or without the rotation columns).
std::vector<std::string> ftable_columns(bool with_rotation);

/// The row that 10 or 14 numbers in the column order above stand for (t, F row-major, then
/// angle_deg and the axis when there are 14): one layout for a file's rows and a deck's.
FTableRow ftable_row(const double* x, size_t count);

/// Reads an F-table file. Errors are DeckErrors naming the file, line and column (key path
/// `key_path`, e.g. "drive.table"); a file that cannot be opened is reported with `key_path`
/// and the path as given.
FTableFile read_ftable_csv(const std::string& path, const std::string& key_path);

/// Checks a table's rows as drive_point would (times strictly increasing, finite values,
/// det F > 0, first row without rotation, non-zero axes) and calls fail(row_index, message) for
/// the first problem (fail must not return).
template <class Fail>
void check_ftable_rows(const std::vector<FTableRow>& rows, Fail&& fail);

}  // namespace ballista

// ---- implementation of the template ------------------------------------------------------------
#include <cmath>

#include "deck/deck_node.hpp"

namespace ballista {

template <class Fail>
void check_ftable_rows(const std::vector<FTableRow>& rows, Fail&& fail) {
  for (size_t k = 0; k < rows.size(); ++k) {
    const FTableRow& r = rows[k];
    if (!std::isfinite(r.t) || !all_finite(r.F) || !std::isfinite(r.angle_deg) || !all_finite(r.axis))
      fail(k, "expected finite numbers");
    if (k > 0 && !(r.t > rows[k - 1].t))
      fail(k, "expected times strictly increasing; " + format_number(r.t) + " follows " + format_number(rows[k - 1].t));
    if (!(det(r.F) >= 1e-6)) fail(k, "expected det F >= 1e-6 (a volume ratio), got " + format_number(det(r.F)));
    if (k == 0 && r.angle_deg != 0.0)
      fail(k,
           "expected rotation angle 0 in the first row (the initial state; a rotation accumulates over "
           "the row that ends at its time), got " +
               format_number(r.angle_deg));
    if (r.angle_deg != 0.0 && !(norm(r.axis) > 0.0)) fail(k, "expected a non-zero rotation axis");
  }
}

}  // namespace ballista
