#pragma once
// Registry of probes, like the solver and material registries. A probe is a scalar measure of the
// current state (history.csv column, summary.json "probes"); each kind registers itself from its
// own file (BALLISTA_REGISTER_PROBE) with its name (probes[].type in the deck), its deck
// parameters and a factory. The deck reader, `ballista info` and the run loop read the registry,
// so no other file names a probe kind. It lives here, below io, so that the deck reader can read
// probes without reaching up; the kinds themselves live in analysis.
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"
#include "core/registry.hpp"
#include "core/solver.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// What a probe sees when it is evaluated.
struct ProbeContext {
  const FieldStore& points;
  const EnergyTotals& energy;
  Dimension dim;
  const Communicator& comm;
  /// Spatial dimensions of the points' motion: 3 in 3D, 2 in plane strain and axisymmetry.
  int nd() const { return dim == Dimension::ThreeD ? 3 : 2; }
};

class Probe {
 public:
  virtual ~Probe() = default;
  /// Throws DeckError at the probe's line if it cannot be evaluated on these points (checked once
  /// the bodies are seeded, e.g. a field that does not exist).
  virtual void check(const FieldStore& points) const {}
  /// The probe's value; NaN when no point qualifies.
  virtual double value(const ProbeContext& ctx) const = 0;
};

/// One deck key of a probe kind and how the deck reader reads it into a ProbeSpec.
struct ProbeParam {
  enum class Kind {
    Body,    ///< optional name of a body ("" = every body), in params.choices
    Axis,    ///< x | y (| z in 3D), in params as 0, 1, 2
    Number,  ///< a number >= min (> min if min_exclusive), in params
    Vector,  ///< the dimension's 2 or 3 components, in vectors
    Word,    ///< a word, one of `choices` unless that is empty, in params.choices
  };
  std::string name;
  Kind kind = Kind::Number;
  std::string unit;          ///< SI unit of a number or vector; "" otherwise
  std::string description;
  bool required = true;      ///< Number and Vector: if false, default_value is used when absent
  double default_value = 0.0;  ///< Vector: every component
  double min = -std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  std::vector<std::string> choices = {};
};

struct ProbeFactory {
  std::string name;                 ///< probes[].type
  std::string description;          ///< one line: what it measures
  std::string unit;                 ///< SI unit of its value; "" for a field's maximum: the field's unit
  std::vector<ProbeParam> params;   ///< read in this order
  /// Checks against the rest of the deck after the parameters are read; throws ParamError naming
  /// the key, which the deck reader reports at that key's line. May be null.
  void (*check)(const ProbeSpec& spec, const Scenario& sc) = nullptr;
  std::unique_ptr<Probe> (*create)(const ProbeSpec& spec, const Scenario& sc) = nullptr;
};

/// Registered probe kinds by name (core/registry.hpp), filled at static-initialisation time.
using ProbeRegistry = Registry<ProbeFactory, &ProbeFactory::name>;
inline const std::vector<ProbeFactory>& probe_registry() { return ProbeRegistry::sorted(); }
inline const ProbeFactory* find_probe(const std::string& name) { return ProbeRegistry::find(name); }

/// The deck's probes, in deck order.
std::vector<std::unique_ptr<Probe>> make_probes(const Scenario& sc);

/// The `body` of a probe as a body index in deck order, -1 for every body.
int probe_body(const ProbeSpec& spec, const Scenario& sc);

}  // namespace ballista

/// Registers one from its own .cpp: BALLISTA_REGISTER_PROBE(ProbeFactory{...}).
#define BALLISTA_REGISTER_PROBE(...) BALLISTA_REGISTER(::ballista::ProbeRegistry, __VA_ARGS__)
