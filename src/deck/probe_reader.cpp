#include "deck/probe_reader.hpp"

#include "deck/body_ref.hpp"
#include "deck/deck_reader.hpp"
#include "points/probe_registry.hpp"

namespace ballista {

namespace {

int components(const Scenario& sc) { return sc.simulation.dimension == Dimension::ThreeD ? 3 : 2; }

std::vector<std::string> axes(const Scenario& sc) {
  return components(sc) == 2 ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x", "y", "z"};
}

/// One parameter of a probe, read as its kind declares (points/probe_registry.hpp).
void probe_param(DeckNode& p, const Scenario& sc, const ProbeParam& param, ProbeSpec& probe) {
  const NumberRange range{.min = param.min, .min_exclusive = param.min_exclusive, .unit = param.unit};
  switch (param.kind) {
    case ProbeParam::Kind::Body:
      probe.params.choices[param.name] = read_body_ref(p, sc, false);
      break;
    case ProbeParam::Kind::Axis:
      probe.params[param.name] = axis_from(p.choice(param.name, axes(sc)));
      break;
    case ProbeParam::Kind::Number:
      probe.params[param.name] = param.required ? p.number(param.name, range)
                                                : p.number(param.name, param.default_value, range);
      break;
    case ProbeParam::Kind::Vector: {
      const double d = param.default_value;
      probe.vectors[param.name] = param.required ? p.vector(param.name, components(sc))
                                                 : p.vector(param.name, Vec3{{d, d, d}}, components(sc));
      break;
    }
    case ProbeParam::Kind::Word:
      probe.params.choices[param.name] =
          param.choices.empty() ? p.string(param.name) : p.choice(param.name, param.choices);
      break;
  }
}

}  // namespace

void read_probes(DeckNode& root, Scenario& sc) {
  DeckNode ps = root.list("probes", false);
  for (size_t i = 0; i < ps.size(); ++i) {
    DeckNode p = ps.element(i);
    ProbeSpec probe;
    probe.mark = p.mark();
    probe.name = p.string("name");
    for (const auto& other : sc.probes)
      if (other.name == probe.name)
        p.fail("name", "duplicate probe name '" + probe.name + "' (also " + other.mark.key_path +
                           (other.mark.line > 0 ? " at line " + std::to_string(other.mark.line) : "") + ")");
    std::vector<std::string> kinds;
    for (const auto& f : probe_registry()) kinds.push_back(f.name);
    probe.type = p.choice("type", kinds);
    const ProbeFactory& kind = *find_probe(probe.type);
    for (const ProbeParam& param : kind.params) probe_param(p, sc, param, probe);
    if (kind.check) {
      try {
        kind.check(probe, sc);
      } catch (const ParamError& e) {
        p.fail(e.param(), e.what());
      }
    }
    p.finish();
    sc.probes.push_back(std::move(probe));
  }
}

}  // namespace ballista
