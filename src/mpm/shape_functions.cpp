// Non-hot helpers of the MPM shape functions: names, parsing, descriptions.
#include "mpm/shape_functions.hpp"

#include <cctype>

#include "core/error.hpp"

namespace ballista {

namespace {
constexpr ShapeKind kAllKinds[] = {ShapeKind::Linear, ShapeKind::Gimp, ShapeKind::Cpdi,
                                   ShapeKind::BSpline3};
}

const char* shape_kind_name(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Linear:
      return "linear";
    case ShapeKind::Gimp:
      return "gimp";
    case ShapeKind::Cpdi:
      return "cpdi";
    case ShapeKind::BSpline3:
      return "bspline3";
  }
  return "unknown";
}

std::vector<std::string> shape_kind_names() {
  std::vector<std::string> names;
  for (ShapeKind k : kAllKinds) names.emplace_back(shape_kind_name(k));
  return names;
}

ShapeKind parse_shape_kind(const std::string& name) {
  std::string lower(name);
  for (char& ch : lower) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  for (ShapeKind k : kAllKinds)
    if (lower == shape_kind_name(k)) return k;
  std::string valid;
  for (ShapeKind k : kAllKinds)
    valid += (valid.empty() ? "" : ", ") + std::string(shape_kind_name(k));
  throw Error("unknown shape function '" + name + "'; valid names: " + valid);
}

std::string shape_kind_description(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::Linear:
      return "linear hat functions, 2^d nodes, C0 (Sulsky, Chen & Schreyer, CMAME 118 (1994) 179)";
    case ShapeKind::Gimp:
      return "uniform GIMP: hat averaged over the particle's undeformed box, 3^d nodes "
             "(Bardenhagen & Kober, CMES 5 (2004) 477)";
    case ShapeKind::Cpdi:
      return "CPDI1: hats averaged over the corners of the deformed parallelogram/parallelepiped "
             "domain (Sadeghirad, Brannon & Burghardt, IJNME 86 (2011) 1435)";
    case ShapeKind::BSpline3:
      return "cubic B-spline, 4^d nodes, C2 (de Boor 1978; Steffen, Kirby & Berzins, IJNME 76 "
             "(2008) 922); boundary-modified at fixed and wall faces (Steffen, Wallstedt et al., "
             "CMES 31 (2008) 107), mirrored at symmetry faces and the axis";
  }
  return "unknown";
}

}  // namespace ballista
