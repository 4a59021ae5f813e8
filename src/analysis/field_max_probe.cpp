// Probe `field_max`: the maximum of a scalar point field over a body (e.g. eqps, damage).
#include <algorithm>
#include <limits>

#include "analysis/body_probe.hpp"
#include "core/error.hpp"

namespace ballista {

namespace {

class FieldMaxProbe : public BodyProbe {
 public:
  FieldMaxProbe(int body, std::string field, DeckMark mark)
      : BodyProbe(body), field_(std::move(field)), mark_(std::move(mark)) {}

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
    const double* f = c.points.real(field_);
    double m = -std::numeric_limits<double>::infinity();
    for_each_point(c.points, [&](Index p) { m = std::max(m, f[p]); });
    return max_over_ranks(m, c.comm);
  }

 private:
  std::string field_;
  DeckMark mark_;  // the probe's place in the deck, for check()
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "field_max",
    .description = "maximum of a scalar particle field over the body",
    .params = {body_param(),
               {.name = "field", .kind = ProbeParam::Kind::Word, .unit = "",
                .description = "a scalar field (e.g. eqps, damage, internal_energy)"}},
    .create = [](const ProbeSpec& spec, const Scenario& sc) -> std::unique_ptr<Probe> {
      return std::make_unique<FieldMaxProbe>(probe_body(spec, sc), spec.params.choice("field"), spec.mark);
    }})

}  // namespace ballista
