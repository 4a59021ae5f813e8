#include "deck/penetrator_reader.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "core/error.hpp"
#include "deck/deck_reader.hpp"
#include "deck/text_file.hpp"

namespace ballista {

namespace {

struct Row {
  double radius, length, velocity, insert_time;
  DeckMark mark;  ///< where the row is (for errors found after reading)
};

/// Axis of flight, direction (+1/-1) and the point on the axis, with the axisymmetric checks.
void read_axis(DeckNode& n, Dimension dim, const std::string& point_key, PenetratorSpec& p) {
  const bool two_d = dim != Dimension::ThreeD;
  const std::vector<std::string> axes =
      two_d ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
  const std::string ax = n.choice("axis", "y", axes);
  p.axis = axis_from(ax);
  const double d = n.number("direction", -1.0, NumberRange::any());
  if (d != 1.0 && d != -1.0)
    n.fail("direction",
           "expected 1 (flies towards +" + ax + ") or -1 (towards -" + ax + "), got " + format_number(d));
  p.direction = d;
  p.nose = n.vector(point_key, two_d ? 2 : 3);
  if (dim == Dimension::Axisymmetric) {
    if (p.axis != 1) n.fail("axis", "expected axis y in an axisymmetric deck (the symmetry axis), got " + ax);
    if (p.nose[0] != 0.0)
      n.fail(point_key, "expected x = 0 in an axisymmetric deck (the point must lie on the axis), got " +
                            format_number(p.nose[0]));
  }
  if (dim == Dimension::PlaneStrain && p.axis == 2) n.fail("axis", "expected x or y in a plane-strain deck");
}

/// A cylinder of the given radius and length whose leading face (the one facing the direction of
/// flight) is at axial coordinate `lead`, on the axis through p.nose.
SegmentSpec make_segment(const PenetratorSpec& p, double lead, double radius, double length, double speed, double t) {
  SegmentSpec s;
  s.shape.type = "cylinder";
  s.shape.axis = p.axis;
  s.shape.radius = radius;
  s.shape.length = length;
  s.shape.center = p.nose;
  // The cylinder's `center` is its base and it extends along +axis.
  s.shape.center[p.axis] = p.direction < 0 ? lead : lead - length;
  s.velocity[p.axis] = p.direction * speed;
  s.activation_time = t;
  return s;
}

/// Fails unless the segment lies inside the grid box along its axis (a jet segment is inserted
/// whole) and its axis lies inside the box (across the axis a symmetry plane or the axisymmetric
/// axis may cut the segment: only the part inside the grid is seeded).
void check_inside_grid(DeckNode& n, const std::string& key, const SegmentSpec& s, const GridSpec& g, int nd,
                       const std::string& what) {
  for (int d = 0; d < nd; ++d) {
    double lo = s.shape.center[d], hi = s.shape.center[d];
    if (d == s.shape.axis) hi = lo + s.shape.length;
    if (lo < g.lower[d] - 1e-12 || hi > g.upper[d] + 1e-12)
      n.fail(key, what + " spans " + format_number(lo) + " to " + format_number(hi) + " m in " + axis_name(d) +
                      ", outside the grid (" + format_number(g.lower[d]) + " to " + format_number(g.upper[d]) + ")");
  }
}

std::vector<Row> inline_rows(DeckNode& jet) {
  std::vector<Row> rows;
  const YAML::Node v = jet.raw("segments");
  const std::string what = "a list of [radius, length, velocity, insert_time] rows (m, m, m/s, s)";
  if (!v.IsSequence() || v.size() == 0) jet.fail("segments", "expected " + what);
  YAML::Node out(YAML::NodeType::Sequence);
  for (size_t i = 0; i < v.size(); ++i) {
    const std::string path = jet.child_path("segments") + "." + std::to_string(i);
    const YAML::Node r = v[i];
    if (!r.IsSequence() || r.size() != 4) deck_fail(jet.context(), path, r.Mark(), "expected " + what);
    double x[4];
    for (int k = 0; k < 4; ++k)
      if (!scalar_number(r[k], x[k]))
        deck_fail(jet.context(), path + "." + std::to_string(k), r[k].Mark(), "expected a number");
    rows.push_back({x[0], x[1], x[2], x[3], deck_mark(jet.context(), path, r.Mark())});
    YAML::Node row(YAML::NodeType::Sequence);
    row.SetStyle(YAML::EmitterStyle::Flow);
    for (double xi : x) row.push_back(format_number(xi));
    out.push_back(row);
  }
  jet.set_resolved("segments", out);
  return rows;
}

/// CSV/blank-separated rows `radius length velocity insert_time`; '#' comment lines and one
/// optional header line of names.
std::vector<Row> file_rows(DeckNode& jet) {
  namespace fs = std::filesystem;
  const std::string name = jet.string("file");
  fs::path path(name);
  if (path.is_relative()) path = fs::path(jet.file()).parent_path() / path;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) jet.fail("file", "cannot open the jet table '" + path.string() + "'");
  std::istringstream in(read_input_file(path.string(), jet.child_path("file"), "the jet table"));
  jet.set_resolved("file", YAML::Node(fs::absolute(path).lexically_normal().string()));
  std::vector<Row> rows;
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const bool blank = line.find_first_not_of(" \t\r") == std::string::npos;
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t' || c == '\r') c = ' ';
    if (!blank && line.find_first_not_of(' ') == std::string::npos)
      throw DeckError(path.string(), line_no, 1, jet.child_path("file"),
                      "a row of separators without numbers (expected radius, length, velocity, insert_time)");
    std::istringstream is(line);
    std::string first;
    if (!(is >> first) || first[0] == '#') continue;
    std::vector<double> x;
    std::istringstream all(line);
    std::string tok, bad;
    bool numeric = true;
    while (all >> tok) {
      char* end = nullptr;
      const double d = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || *end != '\0') numeric = false;
      else if (!std::isfinite(d) && bad.empty()) bad = tok;  // a number, but not a finite one
      x.push_back(d);
    }
    if (!numeric && rows.empty() && line_no == 1) continue;  // header (names, not numbers)
    DeckMark m{path.string(), jet.child_path("file"), line_no, 1};
    if (!numeric || x.size() != 4)
      throw DeckError(m.file, line_no, 1, m.key_path,
                      "expected 4 numbers per row: radius (m), length (m), velocity (m/s), insert_time (s)");
    if (!bad.empty())
      throw DeckError(m.file, line_no, 1, m.key_path, "expected finite numbers, got '" + shorten(bad) + "'");
    rows.push_back({x[0], x[1], x[2], x[3], m});
  }
  if (rows.empty()) jet.fail("file", "the jet table '" + path.string() + "' has no rows");
  return rows;
}

[[noreturn]] void row_fail(const Row& r, const std::string& message) {
  throw DeckError(r.mark.file, r.mark.line, r.mark.column, r.mark.key_path, message);
}

}  // namespace

void read_rod(DeckNode& n, Dimension dim, const GridSpec& grid, BodySpec& body) {
  PenetratorSpec& p = body.penetrator;
  p.kind = "rod";
  read_axis(n, dim, "nose", p);
  p.diameter = n.number("diameter", NumberRange::positive("m"));
  p.length = n.number("length", NumberRange::positive("m"));
  p.speed = n.number("speed", NumberRange::non_negative("m/s"));
  const double ld = n.number("segment_ld", 0.0, NumberRange::non_negative());
  // Segmented rod (thesis seed 000 §6.4): pieces of length L_seg = ld D separated by voids of
  // `gap` (default L_seg, as in the thesis: "separated by a void of the same length").
  int count = 1;
  double seg_length = p.length, gap = 0.0;
  if (ld > 0.0) {
    count = std::max(1, static_cast<int>(std::lround(p.length / (ld * p.diameter))));
    seg_length = p.length / count;  // the material length stays exactly `length`
    gap = n.number("gap", seg_length, NumberRange::non_negative("m"));
    if (count > 10000) n.fail("segment_ld", "expected at most 10000 segments, got " + std::to_string(count));
  } else if (n.has("gap")) {
    n.fail("gap", "a gap needs segment_ld > 0 (a segmented rod)");
  } else {
    n.allow("gap");
  }
  n.finish();
  const int nd = dim == Dimension::ThreeD ? 3 : 2;
  body.segments.clear();
  for (int k = 0; k < count; ++k) {
    const double lead = p.nose[p.axis] - p.direction * k * (seg_length + gap);
    body.segments.push_back(make_segment(p, lead, 0.5 * p.diameter, seg_length, p.speed, body.activation_time));
    check_inside_grid(n, "nose", body.segments.back(), grid, nd,
                      count == 1 ? "the rod" : "segment " + std::to_string(k));
  }
  body.shape = body.segments.front().shape;
  body.velocity = body.segments.front().velocity;
}

void read_jet(DeckNode& n, Dimension dim, const GridSpec& grid, BodySpec& body) {
  PenetratorSpec& p = body.penetrator;
  p.kind = "jet";
  read_axis(n, dim, "face", p);
  const double insert_distance = n.number("insert_distance", NumberRange::positive("m"));
  const double standoff = n.number("standoff", insert_distance, NumberRange::positive("m"));
  if (standoff < insert_distance)
    n.fail("standoff", "expected standoff >= insert_distance (" + format_number(insert_distance) + " m), got " +
                           format_number(standoff));
  const bool inline_table = n.has("segments"), file_table = n.has("file");
  if (inline_table == file_table)
    n.fail("expected either segments (inline rows) or file (a CSV table), not both or neither");
  std::vector<Row> rows = inline_table ? inline_rows(n) : file_rows(n);
  if (inline_table) n.allow("file");
  else n.allow("segments");
  n.finish();
  const int nd = dim == Dimension::ThreeD ? 3 : 2;
  // Thesis seed 000 §5.1: each cylinder waits at rest until its insert time, then is moved along
  // the axis to the insertion point and given its velocity. Here it is seeded at the insertion
  // plane, `insert_distance` in front of the struck face, and becomes active when it gets there:
  // the table's insert time is when it leaves the charge plane (a standoff in front of the face),
  // so it arrives after the free flight (standoff - insert_distance) / V. With standoff =
  // insert_distance the table times are the insertion times.
  const double plane = p.nose[p.axis] - p.direction * insert_distance;
  double mass_diameter = 0.0, mass = 0.0;
  body.segments.clear();
  p.length = 0.0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    if (!(r.radius > 0) || !(r.length > 0) || !(r.velocity > 0) || !(r.insert_time >= 0))
      row_fail(r, "expected radius > 0 (m), length > 0 (m), velocity > 0 (m/s) and insert_time >= 0 (s), got " +
                      format_number(r.radius) + ", " + format_number(r.length) + ", " + format_number(r.velocity) +
                      ", " + format_number(r.insert_time));
    const double t = body.activation_time + r.insert_time + (standoff - insert_distance) / r.velocity;
    body.segments.push_back(make_segment(p, plane, r.radius, r.length, r.velocity, t));
    check_inside_grid(n, inline_table ? "segments" : "file", body.segments.back(), grid, nd,
                      "segment " + std::to_string(k) + " at its insertion");
    p.length += r.length;
    const double m = r.radius * r.radius * r.length;
    mass += m;
    mass_diameter += m * 2.0 * r.radius;
  }
  // No segment may be inserted on top of one inserted earlier that is still crossing the
  // insertion plane (free flight at its own velocity): that would seed overlapping material.
  for (size_t k = 0; k < rows.size(); ++k)
    for (size_t j = 0; j < rows.size(); ++j) {
      if (j == k) continue;
      const double tj = body.segments[j].activation_time, tk = body.segments[k].activation_time;
      if (tj > tk || (tj == tk && j > k)) continue;
      const double travelled = rows[j].velocity * (tk - tj);
      if (travelled < rows[j].length)
        row_fail(rows[k], "segment " + std::to_string(k) + " is inserted at t = " + format_number(tk) +
                              " s while segment " + std::to_string(j) + " (inserted at " + format_number(tj) +
                              " s) still occupies the insertion plane (it has moved " + format_number(travelled) +
                              " m of its " + format_number(rows[j].length) +
                              " m length): increase the insert time or shorten the segments");
    }
  p.diameter = mass > 0 ? mass_diameter / mass : 0.0;
  p.speed = rows.front().velocity;
  p.nose[p.axis] = plane;
  body.shape = body.segments.front().shape;
  body.velocity = body.segments.front().velocity;
}

}  // namespace ballista
