#pragma once
// Registry of loads, like the probe and solver registries: each kind of external force on the
// points registers itself from its own file (BALLISTA_REGISTER_LOAD, files in points/loads/) with
// its name (loads[].type in the deck), how it reads its deck entry, what it marks on the points
// after seeding, and the force it applies. The deck reader, `ballista info` and PointLoads read
// the registry, so no other file names a load kind. It lives here, below the deck reader, which
// gives each kind its entry through LoadEntry.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/field_store.hpp"
#include "core/registry.hpp"
#include "core/tensor.hpp"
#include "scenario/number_range.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// A load's deck entry as its kind reads it. The deck reader implements it over the entry's node:
/// each getter checks the key's type and range and reports an error at its line, and records
/// the value in the resolved deck; fail() reports a kind's own check at the key's line.
class LoadEntry {
 public:
  virtual ~LoadEntry() = default;
  /// `body`: the name of a defined body; "" when absent and not required (every body).
  virtual std::string body(bool required) = 0;
  virtual double number(const std::string& key, const NumberRange& range) = 0;
  virtual double number(const std::string& key, double fallback, const NumberRange& range) = 0;
  /// A vector with the run's components (2 in 2D runs, 3 in 3D).
  virtual Vec3 vector(const std::string& key) = 0;
  virtual Vec3 vector(const std::string& key, const Vec3& fallback) = 0;
  virtual std::string word(const std::string& key, const std::vector<std::string>& choices) = 0;
  virtual std::string string(const std::string& key) = 0;
  virtual std::string string(const std::string& key, const std::string& fallback) = 0;
  virtual bool boolean(const std::string& key, bool fallback) = 0;
  /// `curve`: [time, scale] pairs (s, -), linear between them, constant outside; none: scale 1.
  virtual LoadCurve curve() = 0;
  [[noreturn]] virtual void fail(const std::string& key, const std::string& message) = 0;
  /// The deck read so far: the simulation, the bodies and the loads before this one.
  virtual const Scenario& scenario() const = 0;
};

/// What a kind read from one entry: the loads it stands for (confinement: three pressures), and
/// the stress they should hold the body at in equilibrium (for stages that wait for it), if any.
struct LoadReading {
  std::vector<LoadSpec> loads;
  std::optional<Vec3> equilibrium_stress;  ///< Pa, principal stresses along x, y, z (r, z, theta)
  /// Set when the body is to start in that equilibrium (BodySpec::prestress) rather than be
  /// brought to it by the load's ramp.
  bool prestress = false;
};

/// A force on a point and where it acts (a surface traction at the point's face).
struct SurfaceForce {
  Vec3 point;       ///< m
  Vec3 force;       ///< N
  Index index = 0;  ///< the point it acts on
};

/// The forces of this step that loads add to.
struct LoadForces {
  std::vector<Vec3>& total;                   ///< per point, every load, N (sized to the points)
  std::vector<Vec3>& traction;                ///< per point, surface tractions only; sized by the first that adds one
  std::vector<SurfaceForce>& surface_forces;  ///< each traction with its point of action
};

/// One load of a run, built from its LoadSpec.
class Load {
 public:
  virtual ~Load() = default;
  /// Adds this load's force at `time` (s) on the points.
  virtual void add_forces(const FieldStore& points, double time, LoadForces& out) = 0;
  /// history.csv columns of this load (an indenter's reaction) and their values now.
  virtual std::vector<std::string> history_columns() const { return {}; }
  virtual std::vector<double> history_values() const { return {}; }
};

/// Where the points of a load's body were seeded, for a kind that marks them after seeding.
struct LoadMarkContext {
  const BodySpec& body;  ///< the body as seeded (its particles per cell as the lattice used)
  int body_index = -1;
  double cell_size = 0.0;  ///< m, the seeding lattice's cell
  Dimension dim = Dimension::ThreeD;
};

struct LoadFactory {
  std::string name;         ///< loads[].type
  std::string description;  ///< one line: what it applies, with its source
  /// Reads the entry into loads; `load` comes with its type and mark set (the kind reads the rest,
  /// `body` included). The deck reader rejects keys the kind did not ask for afterwards.
  LoadReading (*read)(LoadEntry& entry, LoadSpec load) = nullptr;
  /// After seeding: marks the points the load needs (a pressure's loaded surface) in fields of
  /// `points` named by the load's index `k`, and returns their names (extensive per-point
  /// quantities); throws DeckError at the load if no point qualifies. May be null.
  std::vector<std::string> (*mark)(const LoadSpec& load, int k, const LoadMarkContext& where,
                                   FieldStore& points) = nullptr;
  /// The load `k` of the deck.
  std::unique_ptr<Load> (*create)(const LoadSpec& load, int k, const Scenario& sc) = nullptr;
};

/// A LoadFactory::create for a load kind L constructed from its spec and the scenario, or from its
/// spec and its index in the deck's loads (which names its marks).
template <class L>
std::unique_ptr<Load> create_load(const LoadSpec& load, int k, const Scenario& sc) {
  if constexpr (std::is_constructible_v<L, const LoadSpec&, const Scenario&>)
    return std::make_unique<L>(load, sc);
  else
    return std::make_unique<L>(load, k);
}

/// Registered load kinds by name (core/registry.hpp), filled at static-initialisation time.
using LoadRegistry = Registry<LoadFactory, &LoadFactory::name>;
inline const std::vector<LoadFactory>& load_registry() { return LoadRegistry::sorted(); }
inline const LoadFactory* find_load(const std::string& name) { return LoadRegistry::find(name); }

/// The deck's loads, in deck order.
std::vector<std::unique_ptr<Load>> make_loads(const Scenario& sc);

}  // namespace ballista

/// Registers one from its own .cpp: BALLISTA_REGISTER_LOAD(LoadFactory{...}).
#define BALLISTA_REGISTER_LOAD(...) BALLISTA_REGISTER(::ballista::LoadRegistry, __VA_ARGS__)
