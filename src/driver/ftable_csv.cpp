#include "driver/ftable_csv.hpp"

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "deck/text_file.hpp"

namespace ballista {

std::vector<std::string> ftable_columns(bool with_rotation) {
  std::vector<std::string> c = {"t"};
  for (int i = 1; i <= 3; ++i)
    for (int j = 1; j <= 3; ++j) c.push_back("F" + std::to_string(i) + std::to_string(j));
  if (with_rotation) c.insert(c.end(), {"angle_deg", "axis_x", "axis_y", "axis_z"});
  return c;
}

FTableRow ftable_row(const double* x, size_t count) {
  FTableRow r;
  r.t = x[0];
  for (int k = 0; k < 9; ++k) r.F.a[k] = x[1 + k];
  if (count == 14) {
    r.angle_deg = x[10];
    r.axis = Vec3{{x[11], x[12], x[13]}};
  }
  return r;
}

namespace {

struct Cell {
  std::string text;
  int column = 0;  ///< 1-based
};

std::vector<Cell> split_cells(const std::string& line) {
  std::vector<Cell> cells;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == ',' || line[i] == '\r')) ++i;
    if (i >= line.size()) break;
    const size_t b = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != ',' && line[i] != '\r') ++i;
    cells.push_back({line.substr(b, i - b), static_cast<int>(b) + 1});
  }
  return cells;
}

bool parse_double(const std::string& s, double& x) {
  const char* b = s.data();
  const char* e = s.data() + s.size();
  if (b != e && *b == '+') ++b;
  const auto r = std::from_chars(b, e, x);
  return r.ec == std::errc() && r.ptr == e && b != e;
}

}  // namespace

FTableFile read_ftable_csv(const std::string& path, const std::string& key_path) {
  std::istringstream in(read_input_file(path, key_path, "the F-table file"));
  FTableFile out;
  std::string line;
  int lineno = 0;
  size_t expected = 0;  // cells per row once known (header or first row)
  bool header_allowed = true;
  const std::string what = "t F11 F12 F13 F21 F22 F23 F31 F32 F33 [angle_deg axis_x axis_y axis_z]";
  while (std::getline(in, line)) {
    ++lineno;
    const auto cells = split_cells(line);
    if (cells.empty() && line.find_first_not_of(" \t\r") != std::string::npos)
      throw DeckError(path, lineno, 1, key_path, "a row of separators without numbers (expected " + what + ")");
    if (cells.empty() || cells[0].text[0] == '#') continue;
    double x = 0.0;
    if (header_allowed && !parse_double(cells[0].text, x)) {
      // A header line: must name the columns exactly.
      header_allowed = false;
      const auto c10 = ftable_columns(false), c14 = ftable_columns(true);
      const auto& ref = cells.size() > 10 ? c14 : c10;
      for (size_t k = 0; k < cells.size() || k < ref.size(); ++k) {
        if (k >= cells.size() || k >= ref.size() || cells[k].text != ref[k])
          throw DeckError(path, lineno, k < cells.size() ? cells[k].column : static_cast<int>(line.size()) + 1,
                          key_path,
                          "expected the header " + join_names(c10) +
                              " (optionally followed by angle_deg, axis_x, "
                              "axis_y, axis_z)" +
                              (k < cells.size() ? ", got '" + cells[k].text + "'" : ", got fewer columns"));
      }
      expected = cells.size();
      continue;
    }
    header_allowed = false;
    if (expected == 0) {
      if (cells.size() != 10 && cells.size() != 14)
        throw DeckError(path, lineno, cells[0].column, key_path,
                        "expected 10 or 14 numbers (" + what + "), got " + std::to_string(cells.size()));
      expected = cells.size();
    } else if (cells.size() != expected) {
      throw DeckError(path, lineno, cells[0].column, key_path,
                      "expected " + std::to_string(expected) + " numbers like the rows above (" + what + "), got " +
                          std::to_string(cells.size()));
    }
    double v[14];
    for (size_t k = 0; k < cells.size(); ++k)
      if (!parse_double(cells[k].text, v[k]))
        throw DeckError(path, lineno, cells[k].column, key_path, "expected a number, got '" + cells[k].text + "'");
    out.rows.push_back(ftable_row(v, cells.size()));
    out.lines.push_back(lineno);
  }
  if (in.bad()) throw DeckError(path, 0, 0, key_path, "cannot read the F-table file");
  if (out.rows.size() < 2)
    throw DeckError(
        path, lineno, 0, key_path,
        "expected at least 2 rows (the initial state and one more), got " + std::to_string(out.rows.size()));
  check_ftable_rows(out.rows, [&](size_t k, const std::string& msg) {
    throw DeckError(path, out.lines[k], 1, key_path, "row at t = " + format_number(out.rows[k].t) + ": " + msg);
  });
  return out;
}

}  // namespace ballista
