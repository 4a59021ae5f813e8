// Probe `field_max`: the maximum of a scalar point field over a body (e.g. eqps, damage).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "core/point_fields.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

class FieldMaxProbe : public Probe {
 public:
  FieldMaxProbe(int body, std::string field, DeckMark mark)
      : body_(body), field_(std::move(field)), mark_(std::move(mark)) {}

  /// The field is known only once the materials have declared their state fields.
  void check(const FieldStore& points) const override {
    if (points.has(field_) && points.info(field_).ncomp == 1 && points.info(field_).type == FieldType::Real) return;
    std::string names;
    for (const auto& fi : points.fields())
      if (fi.ncomp == 1 && fi.type == FieldType::Real) names += (names.empty() ? "" : ", ") + fi.name;
    throw DeckError(mark_.file, mark_.line, mark_.column, mark_.key_path + ".field",
                    "field_max needs a scalar field; '" + field_ + "' is not one (scalar fields: " + names + ")");
  }

  double value(const ProbeContext& c) const override {
    const Index n = c.points.size();
    const auto* bid = c.points.ints(kBodyIndex);
    const double* f = c.points.real(field_);
    double m = -std::numeric_limits<double>::infinity();
    for (Index p = 0; p < n; ++p)
      if (body_ < 0 || bid[p] == body_) m = std::max(m, f[p]);
    m = c.comm.max(m);
    return m > -std::numeric_limits<double>::infinity() ? m : std::nan("");
  }

 private:
  int body_;  // deck order, -1 = every body
  std::string field_;
  DeckMark mark_;  // the probe's place in the deck, for check()
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "field_max",
    .description = "maximum of a scalar particle field over the body",
    .params = {{.name = "body", .kind = ProbeParam::Kind::Body, .unit = "",
                .description = "body measured (default: every body)"},
               {.name = "field", .kind = ProbeParam::Kind::Word, .unit = "",
                .description = "a scalar field (e.g. eqps, damage, internal_energy)"}},
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<FieldMaxProbe>(probe_body(spec, sc), spec.params.choice("field"), spec.mark);
    }})

}  // namespace ballista
