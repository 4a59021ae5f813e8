// Probe `energy`: one of the energy totals of the whole run, J.
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

class EnergyProbe : public Probe {
 public:
  explicit EnergyProbe(std::string which) : which_(std::move(which)) {}

  double value(const ProbeContext& c) const override {
    const EnergyTotals& e = c.energy;
    if (which_ == "kinetic") return e.kinetic;
    if (which_ == "internal") return e.internal;
    if (which_ == "plastic") return e.plastic;
    if (which_ == "external") return e.external;
    return e.total();
  }

 private:
  std::string which_;
};

}  // namespace

BALLISTA_REGISTER_PROBE(ProbeFactory{
    .name = "energy",
    .description = "one of the energy totals [J]",
    .unit = "J",
    .params = {{.name = "field", .kind = ProbeParam::Kind::Word, .unit = "", .description = "which total",
                .choices = {"kinetic", "internal", "plastic", "external", "total"}}},
    .create = [](const ProbeSpec& spec, const Scenario&) -> std::unique_ptr<Probe> {
      return std::make_unique<EnergyProbe>(spec.params.choice("field"));
    }})

}  // namespace ballista
