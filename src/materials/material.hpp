#pragma once
// Material interface shared by every solver and the single-element driver.
//
// A model is written once as a pure per-point kernel (see linear_elastic.cpp for the pattern):
//   struct Model {
//     static constexpr const char* kName;           // deck name
//     struct Params {...};                          // named parameters, SI units
//     static std::vector<ParamSpec> param_specs();  // names, units, defaults, ranges (deck + info)
//     static Params make(const ParamValues&);       // derive/cross-check, throws ParamError
//     static std::vector<StateFieldSpec> state_fields();  // internal variables (become fields)
//     static void update(const Params&, const PointKinematics&, Mat3& sigma_bar, double* state,
//                        PointResult&);             // unrotated-frame stress update
//     static double wave_speed(const Params&, const double* state, double J);
//   };
// MaterialAdapter<Model> (material_adapter.hpp) turns it into a Material that updates a batch of
// points stored in a FieldStore: it does the polar decomposition, rotates into the unrotated
// frame (thesis seed 000 eq. 2.6), calls the kernel and rotates back. The kernel itself never
// sees the rotation, so every model is objective by construction.
#include <atomic>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/field_store.hpp"
#include "core/point_fields.hpp"
#include "core/registry.hpp"
#include "core/tensor.hpp"

namespace ballista {

/// One material parameter as the deck and `ballista info` see it.
struct ParamSpec {
  std::string name;
  std::string unit;         ///< SI unit; "1" for dimensionless
  std::string description;
  bool required = true;     ///< if false, default_value is used when absent
  double default_value = 0.0;
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  bool max_exclusive = false;
  /// Non-empty for an enumerated (word) parameter, e.g. eos.type: {linear, mie_gruneisen}; its
  /// value is then a string in ParamValues::choices and default_choice is used when absent.
  std::vector<std::string> choices = {};
  std::string default_choice = {};
  /// A whole number (read as an integer from the deck: no decimal point), e.g. mpm.sort_every.
  bool integer = false;
  /// Names containing a dot ("eos.hugoniot_slope", "failure.criterion") are read from a sub-map
  /// of the material in the deck (eos: {hugoniot_slope: 1.49}).
};

/// Parameter values by name, already range-checked against the ParamSpecs. Numbers are in the map
/// itself (NaN = an optional parameter that was not given); enumerated parameters in `choices`.
struct ParamValues : std::map<std::string, double> {
  using std::map<std::string, double>::map;
  std::map<std::string, std::string> choices;

  /// True if the number `name` was given (present and not NaN).
  bool given(const std::string& name) const {
    auto it = find(name);
    return it != end() && !(it->second != it->second);
  }
  /// The number `name`, or `fallback` if it was not given.
  double number_or(const std::string& name, double fallback) const { return given(name) ? at(name) : fallback; }
  /// The word `name`, or `fallback` if absent.
  std::string choice(const std::string& name, const std::string& fallback = {}) const {
    auto it = choices.find(name);
    return it == choices.end() ? fallback : it->second;
  }
};

/// `given` with every parameter of `specs` it lacks at its default: for programmatic callers of
/// Model::make (the deck reader fills the defaults itself).
inline ParamValues with_defaults(const ParamValues& given, const std::vector<ParamSpec>& specs) {
  ParamValues v = given;
  for (const ParamSpec& s : specs) {
    if (!s.choices.empty()) {
      if (!v.choices.count(s.name)) v.choices[s.name] = s.default_choice;
    } else if (!v.given(s.name)) {
      v[s.name] = s.default_value;
    }
  }
  return v;
}

/// Thrown by Model::make for a bad combination of parameters; `param` names the deck key so the
/// deck layer can point at its line.
class ParamError : public Error {
 public:
  ParamError(std::string param, const std::string& message) : Error(message), param_(std::move(param)) {}
  const std::string& param() const { return param_; }

 private:
  std::string param_;
};

/// An internal state variable of a model; stored as a per-point field of this name.
struct StateFieldSpec {
  std::string name;
  std::string unit;
  double initial = 0.0;
  /// False for a field of discrete values (a failure flag, a counter), which may not be averaged
  /// between points (OTM's split interpolates the continuous ones).
  bool continuous = true;
};

/// What a kernel is given for one point over one step [t_n, t_{n+1}].
struct PointKinematics {
  Mat3 F_old;   ///< deformation gradient at t_n (filled only if Model::kNeedsFOld is true)
  Mat3 F_new;   ///< deformation gradient at t_{n+1}
  Mat3 R_new;   ///< rotation of F_new = R U
  Mat3 D_bar;   ///< unrotated rate of deformation R^T sym(L) R, 1/s (thesis eq. 2.6)
  double J_old = 1.0;  ///< det F_old (always filled)
  double J_new = 1.0;  ///< det F_new (always filled)
  double dt = 0.0;
  double time = 0.0;   ///< s, t_{n+1} (the solvers' clock; read by the explosive's program burn)
};

/// Per-point by-products of a kernel call. Everything but plastic_work_density is read only by
/// the failure criteria (materials/failure.hpp) and by the single-element driver.
struct PointResult {
  double plastic_work_density = 0.0;  ///< plastic dissipation over the step, J/m^3 (current volume)
  double delta_eqps = 0.0;            ///< increment of equivalent plastic strain over the step
  double eqps = 0.0;                  ///< equivalent plastic strain at t_{n+1}
  double temperature = std::numeric_limits<double>::quiet_NaN();  ///< K at t_{n+1}; NaN if not tracked
  /// (T - T0)/(T_melt - T0) at t_{n+1} (Johnson-Cook T*; melt at 1); NaN if not tracked.
  double homologous_temperature = std::numeric_limits<double>::quiet_NaN();
  /// (sigma_{n+1} - sigma_n) : Delta eps^p over the step, J/m^3 (unrotated frame): Drucker's
  /// stability product (thesis eq. 6.9, times dt^2); 0 for an elastic step.
  double drucker_product = 0.0;
  /// Optional out (set by the caller, e.g. the FD-tangent check): the algorithmic tangent
  /// d sigma_bar_{n+1} / d eps, eps = D_bar dt, as a 6x6 row-major matrix in the order
  /// (11, 22, 33, 23, 13, 12) with tensor (not engineering) shear strains. Models that have one
  /// fill it when it is non-null; others leave it untouched.
  double* tangent = nullptr;
};

/// Pointers to the arrays a batch update reads and writes (all indexed by point). Optional
/// pointers may be null; the solvers use the energy accumulators so that the update, the energy
/// bookkeeping and the finiteness check happen in one pass over memory.
struct MaterialBatch {
  const Index* points = nullptr;  ///< indices of the points of this material
  Index count = 0;
  const Mat3* F_old = nullptr;    ///< F at t_n; if null it is recovered as (I + dt L)^-1 F_new
  Mat3* F_new = nullptr;          ///< F at t_{n+1}; erosion option zero_stress resets it to F_n
  const Mat3* L = nullptr;        ///< velocity gradient over the step, 1/s
  Mat3* R = nullptr;              ///< in: rotation at t_n; out: rotation at t_{n+1}
  Mat3* stress = nullptr;         ///< in: Cauchy stress at t_n; out: at t_{n+1}, Pa
  double* plastic_work = nullptr; ///< optional out: plastic dissipation over the step, J/m^3
  FieldStore* store = nullptr;    ///< holds the model's state fields
  double dt = 0.0;
  double time = 0.0;              ///< s, t_{n+1}
  // Optional energy accumulation (all three set, or none):
  const double* volume0 = nullptr;   ///< reference volume, m^3
  double* internal_energy = nullptr; ///< += dt <V> <sigma> : D (trapezoidal stress power), J
  double* plastic_energy = nullptr;  ///< += plastic dissipation density * V_{n+1}, J
  /// Optional out: 36 doubles per point, the algorithmic tangent (see PointResult::tangent).
  double* tangent = nullptr;
  /// Optional: lowest index of a point whose new stress is not finite (atomic minimum).
  std::atomic<Index>* first_bad = nullptr;
  /// Distortion limit lambda of the models whose stress does not depend on F's isochoric part
  /// (hypoelastic-plastic, fluids: all but the hyperelastic ones). A point whose RMS isochoric
  /// stretch sqrt(tr(C) / (3 J^(2/3))) exceeds it has F replaced by J^(1/3) R_{n+1} (see
  /// distortion.hpp); 0: never. Counted in `distortion_remaps` if it is set.
  double distortion_limit = 0.0;
  std::atomic<Index>* distortion_remaps = nullptr;
};

class Material {
 public:
  virtual ~Material() = default;
  virtual const std::string& name() const = 0;   ///< user's name for this material
  virtual const char* model() const = 0;          ///< deck model name
  virtual double density() const = 0;            ///< reference density rho0, kg/m^3
  virtual std::vector<StateFieldSpec> state_fields() const = 0;
  /// Declares the model's state fields in `store` (idempotent).
  void declare_fields(FieldStore& store) const {
    for (const auto& s : state_fields()) store.add_real(s.name, 1, s.unit, true, s.initial);
  }
  /// Sets this material's state fields of points [begin, end) to their initial values. A field is
  /// shared by every material that has it but starts per material (e.g. the temperature at each
  /// material's initial_temperature), so a solver calls this for the points it seeds.
  void initialise_state(FieldStore& store, Index begin, Index end) const {
    for (const auto& s : state_fields()) {
      double* f = store.real(s.name);
      for (Index p = begin; p < end; ++p) f[p] = s.initial;
    }
  }
  /// Stress update of a batch of points (parallel inside; results independent of thread count).
  virtual void update(const MaterialBatch& batch) const = 0;
  /// Initial stress for a point with deformation gradient F and no history (e.g. a prestrained
  /// manufactured-solution start); hypoelastic models return zero.
  virtual Mat3 initial_stress(const Mat3& F) const = 0;
  /// Largest dilatational wave speed of point p (m/s), J = det F.
  virtual double wave_speed(const FieldStore& store, Index p, double J) const = 0;
  /// max over the points of (wave speed + |v|), m/s: the signal speed of the Courant condition.
  virtual double max_signal_speed(const FieldStore& store, const Index* points, Index count) const = 0;
  /// The dilatational wave speed of each of the points, m/s, into c[p] (indexed by point, not by k).
  virtual void wave_speeds(const FieldStore& store, const Index* points, Index count, double* c) const = 0;
  /// wave_speed(store, points[k], J[k]) into c[k] (indexed by k), the state fields looked up once
  /// for all the points (wave_speed looks them up by name at each call).
  virtual void wave_speeds_at(const FieldStore& store, const Index* points, Index count, const double* J,
                              double* c) const = 0;
  /// The same with each point's EOS energy density (kEosEnergyField) at its reference value, zero:
  /// the wave speed the point would have at its J and state had nothing heated it. Models without
  /// that field give wave_speeds. The linear term of the artificial bulk viscosity reads it under
  /// mpm.bulk_viscosity_sound_speed: reference (mpm/bulk_viscosity.hpp).
  virtual void reference_wave_speeds(const FieldStore& store, const Index* points, Index count, double* c) const = 0;
  /// True if the model keeps the EOS energy density (kEosEnergyField, J/m^3 of reference volume):
  /// heat from outside the model (artificial viscosity) must enter it to reach its pressure.
  bool has_state(const std::string& field) const {
    for (const auto& s : state_fields())
      if (s.name == field) return true;
    return false;
  }
  /// True if the material's failed points carry no stress at all (erosion zero_stress): they
  /// must not resist compression through anything else either (artificial viscosity).
  virtual bool failed_points_are_stress_free() const { return false; }
  /// True if a point at rest and stress-free can change by its own clock (an explosive lit by the
  /// program burn): the multi-rate step never leaves such a point idle (mpm/multirate_idle.cpp).
  virtual bool changes_at_rest() const { return false; }
};

/// The batch every caller of Material::update builds: `count` points of `store` with the common
/// point fields (F at t_{n+1}, L, R, stress; F_old recovered from F_new and L inside the adapter)
/// and, with `energies`, the accumulators volume0, internal_energy and plastic_work. Solvers, the
/// single-element driver and the peridynamic moduli probe all go through it.
inline MaterialBatch make_batch(FieldStore& store, const Index* points, Index count, double dt, bool energies) {
  MaterialBatch b;
  b.points = points;
  b.count = count;
  b.F_old = nullptr;
  b.F_new = store.view(kDeformationGradient);
  b.L = store.view(kVelocityGradient);
  b.R = store.view(kRotation);
  b.stress = store.view(kStress);
  b.store = &store;
  b.dt = dt;
  if (energies) {
    // dE = dt <V> <sigma> : D (trapezoidal stress power); plastic dissipation from the model.
    b.volume0 = store.real(kReferenceVolume);
    b.internal_energy = store.real(kInternalEnergy);
    b.plastic_energy = store.real(kPlasticWork);
  }
  return b;
}

/// A pressure-dependent plasticity problem of the verification catalogue (A3 Drucker-Prager vertex,
/// A4 hydrostat against a cap, A5 load-unload-reload with and without pore fluid): the parameters a
/// geomaterial model is reduced to. Sign convention: tension positive, I1 = tr(sigma).
struct GeoReduction {
  double density = 0;       ///< kg/m^3
  double bulk = 0;          ///< drained bulk modulus K, Pa (constant)
  double shear = 0;         ///< shear modulus G, Pa (constant)
  double peak_i1 = 0;       ///< tensile vertex of the linear Drucker-Prager surface on the I1 axis, Pa
  double fslope = 0;        ///< its slope d sqrt(J2) / d(-I1)
  double cap_ratio = 0;     ///< cap eccentricity CR (major I1 radius over minor sqrt(J2) radius)
  double p0 = 0, p1 = 0, p3 = 0;  ///< crush curve (thesis seed 000 eq. 4.5-4.6); p3 = 0: no porosity, no cap
  bool fixed_cap = false;   ///< cap frozen at p0 (no hardening)
  /// Non-associativity: isotropic part of the plastic flow direction scaled by beta (1:
  /// associative). The published analytic stresses of the A3 vertex test (Brannon &
  /// Leelavanichkul 2010) need beta = 1/2: the test is designed so that on its second leg the
  /// trial-stress rate is parallel to the return direction P = C:M, which in (z = I1/sqrt3,
  /// r = sqrt(2 J2)) is (3K beta f_z, 2G f_r); with K = 10000, G = 3750, f_z/f_r = r0/z0 =
  /// 1/sqrt3 and the leg's trial direction (dz, dr) = (400/sqrt3, 200), parallelism gives
  /// beta = 0.5 exactly (beta = 1 would leave the stress moving along the surface instead of
  /// dwelling).
  double flow_beta = 1.0;
  double fluid_bulk = 0;    ///< pore-fluid bulk modulus, Pa (0: drained)
  double pore_pressure0 = 0;  ///< initial pore pressure, Pa
};

/// How a model is made from the deck; one per registered model.
struct MaterialFactory {
  std::string model;
  std::string description;
  std::vector<ParamSpec> params;
  std::vector<StateFieldSpec> state_fields;
  std::unique_ptr<Material> (*create)(const std::string& name, const ParamValues& values) = nullptr;
  // For the verification suite (ballista verify, CATALOGUE §A). Each is null if the model does not
  // provide it (Model::example_params, Model::reduce_to_elastic, Model::reduce_to_j2).
  /// A representative parameter set (A6 objectivity and tangent checks).
  ParamValues (*example)() = nullptr;
  /// Parameters that reduce the model to isotropic linear elasticity with K, G (A1).
  ParamValues (*reduce_elastic)(double density, double bulk, double shear) = nullptr;
  /// Parameters that reduce the model to J2 plasticity with uniaxial yield stress sigma_y0, linear
  /// isotropic plastic modulus H_iso and linear kinematic modulus H_kin (A2 and its variants); may
  /// return an empty ParamValues if the model lacks the requested hardening kind.
  ParamValues (*reduce_j2)(double density, double bulk, double shear, double yield, double h_iso,
                           double h_kin) = nullptr;
  /// Parameters that reduce the model to a linear Drucker-Prager surface with an optional
  /// elliptical cap, crush curve and pore fluid (A3-A5); null for models without pressure-dependent
  /// strength.
  ParamValues (*reduce_geo)(const GeoReduction& g) = nullptr;
};

/// Registered models by name (core/registry.hpp), filled at static-initialisation time by one
/// line per model file (BALLISTA_REGISTER_MATERIAL); read-only afterwards.
using MaterialRegistry = Registry<MaterialFactory, &MaterialFactory::model>;
inline const std::vector<MaterialFactory>& material_registry() { return MaterialRegistry::sorted(); }
inline const MaterialFactory* find_material(const std::string& model) { return MaterialRegistry::find(model); }

}  // namespace ballista
