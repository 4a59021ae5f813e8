#include "penetration/model_catalog.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "penetration/harvey.hpp"
#include "penetration/hydrodynamic.hpp"
#include "penetration/orphal_anderson.hpp"
#include "penetration/pack_evans_fit.hpp"
#include "penetration/strength_models.hpp"
#include "penetration/tate.hpp"
#include "penetration/walters_segletes.hpp"

namespace ballista::penetration {

namespace {

ModelParam req(std::string key, std::string unit, std::string description) {
  return {std::move(key), std::move(unit), std::move(description), true, 0, false};
}
ModelParam opt(std::string key, std::string unit, std::string description, double def) {
  return {std::move(key), std::move(unit), std::move(description), false, def, false};
}
ModelParam maybe(std::string key, std::string unit, std::string description) {
  return {std::move(key), std::move(unit), std::move(description), false, 0, true};
}
ModelOutput num(std::string key, std::string unit, double v) {
  return {std::move(key), std::move(unit), v, {}};
}
ModelOutput word(std::string key, std::string text) {
  return {std::move(key), "", 0, std::move(text)};
}

PackEvansForm form_of(const ModelArgs& a) {
  const double f = a.at("penalty_outside_root");
  if (f != 0 && f != 1) throw Error(fmt::format("penalty_outside_root = {:g} must be 0 (eq. 3.5) or 1 (§6.4)", f));
  return f == 1 ? PackEvansForm::kPenaltyOutsideRoot : PackEvansForm::kPenaltyInsideRoot;
}

std::vector<ModelOutput> steady_outputs(const SteadyPenetration& s) {
  return {num("U", "m/s", s.U), num("P", "m", s.P), word("regime", to_string(s.regime))};
}

/// The parameters most models share.
struct CommonParams {
  ModelParam L, rho_p, rho_t, V, R, Y;
};

/// The shared parameters, spelled once so that every model that takes them lists them alike.
CommonParams common_params() {
  return {req("L", "m", "jet or rod length"),
          req("rho_p", "kg/m^3", "jet or rod density"),
          req("rho_t", "kg/m^3", "target density"),
          req("V", "m/s", "impact velocity (sweep with --velocities)"),
          req("R", "Pa", "target dynamic resistance"),
          req("Y", "Pa", "penetrator dynamic strength")};
}

/// Steady jets (eq. 3.1-3.8): Birkhoff's hydrodynamic jet and its corrections for particulation,
/// target strength as a penalty, and strength on both sides (Eichelberger).
void add_steady_jet_models(std::vector<ModelEntry>& m, const CommonParams& common) {
  const auto& [L, rho_p, rho_t, V, R, Y] = common;
  m.push_back({"birkhoff",
               "thesis seed 000 eq. 3.1-3.2, §5.2 (U_h)",
               "hydrodynamic jet: depth L sqrt(rho_p/rho_t), penetration velocity V/(1 + sqrt(rho_t/rho_p))",
               {L, rho_p, rho_t, maybe("V", "m/s", "jet velocity (for U_h; sweep with --velocities)")},
               false,
               [](const ModelArgs& a) {
                 std::vector<ModelOutput> o{num("P", "m", birkhoff_depth(a.at("L"), a.at("rho_p"), a.at("rho_t")))};
                 if (a.has("V"))
                   o.insert(o.begin(), num("U", "m/s",
                                           hydrodynamic_penetration_velocity(a.at("V"), a.at("rho_p"), a.at("rho_t"))));
                 return o;
               }});
  m.push_back({"particulated-jet",
               "thesis seed 000 eq. 3.3-3.4",
               "Birkhoff with particulation: lambda rho_avg (V-U)^2 = rho_t U^2, P = L sqrt(lambda rho_avg/rho_t)",
               {L, req("lambda", "1", "particulation, 1 (continuous) to 2 (fully particulated)"),
                req("rho_avg", "kg/m^3", "jet mass over its convex-hull volume"), rho_t,
                maybe("V", "m/s", "jet velocity (for U; sweep with --velocities)")},
               false,
               [](const ModelArgs& a) {
                 std::vector<ModelOutput> o{
                     num("P", "m", particulated_jet_depth(a.at("L"), a.at("lambda"), a.at("rho_avg"), a.at("rho_t")))};
                 if (a.has("V"))
                   o.insert(o.begin(),
                            num("U", "m/s",
                                particulated_jet_velocity(a.at("V"), a.at("lambda"), a.at("rho_avg"), a.at("rho_t"))));
                 return o;
               }});
  m.push_back(
      {"pack-evans",
       "thesis seed 000 eq. 3.5 (penalty form of §6.4 eq. 6.15-6.16 optional)",
       "target strength as a penalty on Birkhoff, plus the channel radius as secondary penetration",
       {L, opt("lambda", "1", "particulation factor", 1), rho_p, rho_t,
        req("alpha", "1", "density-dependent penalty coefficient"), req("sigma_y", "Pa", "target yield strength"), V,
        opt("r", "m", "channel radius (secondary penetration)", 0),
        opt("penalty_outside_root", "1", "0: eq. 3.5 as printed; 1: penalty outside the root (§6.4)", 0)},
       false,
       [](const ModelArgs& a) {
         PackEvansInput in{a.at("L"),       a.at("lambda"), a.at("rho_p"), a.at("rho_t"), a.at("alpha"),
                           a.at("sigma_y"), a.at("V"),      a.at("r"),     form_of(a)};
         return std::vector<ModelOutput>{num("penalty", "1", pack_evans_penalty(in)),
                                         num("P", "m", pack_evans_depth(in))};
       }});
  m.push_back({"eichelberger",
               "thesis seed 000 eq. 3.6-3.8",
               "lambda rho_p (V-U)^2 = rho_t U^2 + 2 (R - Y), P = L sqrt(lambda rho_p/rho_t - 2(R-Y)/(rho_t (V-U)^2))",
               {L, opt("lambda", "1", "statistical jet factor", 1), rho_p, rho_t, R, Y, V},
               false,
               [](const ModelArgs& a) {
                 return steady_outputs(eichelberger(
                     {a.at("L"), a.at("lambda"), a.at("rho_p"), a.at("rho_t"), a.at("R"), a.at("Y"), a.at("V")}));
               }});
}

/// Penetrators that are not a steady continuous jet (eq. 3.9-3.13): the eroding rod in time
/// (Tate), the stretching jet (Gladkikh), the porous jet (Grove).
void add_penetrator_variant_models(std::vector<ModelEntry>& m, const CommonParams& common) {
  const auto& [L, rho_p, rho_t, V, R, Y] = common;
  m.push_back({"tate",
               "thesis seed 000 eq. 3.9; Walters & Segletes, Int. J. Impact Eng. 11 (1991) 225",
               "Alekseevskii-Tate eroding rod integrated in time (RK4, step control, events), then rigid if Y > R; "
               "the eroding phase also from the Walters-Segletes exact solution",
               {L, rho_p, rho_t, R, Y, V, opt("steps_per_transit", "1", "RK4 steps per L/V (accuracy)", 200)},
               false,
               [](const ModelArgs& a) {
                 const TateInput in{a.at("L"), a.at("rho_p"), a.at("rho_t"), a.at("R"), a.at("Y"), a.at("V")};
                 TateOptions opt;
                 opt.steps_per_transit = static_cast<int>(a.at("steps_per_transit"));
                 if (opt.steps_per_transit < 1)
                   throw Error(fmt::format("tate: steps_per_transit = {:g} must be >= 1", a.at("steps_per_transit")));
                 opt.record_history = false;
                 const TateRun run = integrate_tate(in, opt);
                 std::vector<ModelOutput> o{num("U0", "m/s", tate_penetration_velocity(in, in.V0).U),
                                            num("P", "m", run.final.P),
                                            num("L_final", "m", run.final.L),
                                            num("V_final", "m/s", run.final.V),
                                            num("t_final", "s", run.final.t),
                                            word("stop", run.stop_reason),
                                            num("steps", "", static_cast<double>(run.steps))};
                 if (in.Y > 0 && tate_penetration_velocity(in, in.V0).regime == InterfaceRegime::kEroding) {
                   const TateState ex = walters_segletes_final(in);
                   o.push_back(num("P_erosion_exact", "m", ex.P));
                   o.push_back(num("t_erosion_exact", "s", ex.t));
                 }
                 return o;
               }});
  m.push_back({"gladkikh",
               "thesis seed 000 eq. 3.10",
               "constant-diameter jet with a linear velocity gradient (needs V_tip/V_tail > 1)",
               {L, rho_p, rho_t, req("V_tip", "m/s", "jet tip velocity"), req("V_tail", "m/s", "jet tail velocity")},
               false,
               [](const ModelArgs& a) {
                 return std::vector<ModelOutput>{num(
                     "P", "m", gladkikh_depth(a.at("L"), a.at("rho_p"), a.at("rho_t"), a.at("V_tip"), a.at("V_tail")))};
               }});
  m.push_back({"grove",
               "thesis seed 000 eq. 3.11-3.13",
               "porous (distended) jet: shock compaction, then Eichelberger with lambda = 1 + phi",
               {L, req("rho_d", "kg/m^3", "distended jet density"), req("rho_s", "kg/m^3", "solid jet density"), rho_t,
                R, Y, V},
               false,
               [](const ModelArgs& a) {
                 const GroveResult g =
                     grove({a.at("L"), a.at("rho_d"), a.at("rho_s"), a.at("rho_t"), a.at("R"), a.at("Y"), a.at("V")});
                 auto o = steady_outputs(g.steady);
                 o.insert(o.begin(), num("phi", "1", g.phi));
                 return o;
               }});
}

/// Orphal-Anderson's strength difference implied by U = a + b V (eq. 5.3-5.5), appended to `o`:
/// shared by the model given a and b and the one that fits them.
void append_orphal_anderson_outputs(double a_, double b_, const ModelArgs& a, std::vector<ModelOutput>& o) {
  const double rp = a.at("rho_p"), rt = a.at("rho_t");
  const double curv = orphal_anderson_curvature(b_, rp, rt);
  o.push_back(num("curvature", "kg/m^3", curv));
  o.push_back(num("b_hydrodynamic", "1", orphal_anderson_hydrodynamic_slope(rp, rt)));
  if (curv != 0) {
    o.push_back(num("V_m", "m/s", orphal_anderson_extremum_velocity(a_, b_, rp, rt)));
    o.push_back(word("extremum", curv < 0 ? "maximum" : "minimum"));
  }
  if (a.has("V")) o.push_back(num("R_minus_Y", "Pa", orphal_anderson_strength_difference(a_, b_, rp, rt, a.at("V"))));
}

/// Models fitted to or read back from measurements: Harvey's stressed-rock correlation
/// (eq. 3.14-3.18), Orphal-Anderson's U = a + b V (eq. 5.2-5.5), Pack-Evans inverted for alpha and
/// lambda (eq. 6.15-6.16).
void add_empirical_models(std::vector<ModelEntry>& m, const CommonParams& common) {
  const auto& [L, rho_p, rho_t, V, R, Y] = common;
  m.push_back({"harvey",
               "thesis seed 000 eq. 3.14-3.18 (field units inside, SI here)",
               "stressed-rock correlation P = P_ref exp(alpha0 (10000 psi - F_BI)); eq. 3.16 read as P_c - a P_p",
               {req("P_ref", "m", "depth at F_BI = 10000 psi"), req("alpha0", "1/Pa", "charge coefficient"),
                req("sigma_ucs", "Pa", "unconfined compressive strength"), req("P_c", "Pa", "confining stress"),
                req("P_p", "Pa", "pore pressure"), req("porosity", "1", "porosity fraction in [0, 1]")},
               false,
               [](const ModelArgs& a) {
                 const HarveyResult h = harvey_depth(
                     {a.at("P_ref"), a.at("alpha0"), a.at("sigma_ucs"), a.at("P_c"), a.at("P_p"), a.at("porosity")});
                 return std::vector<ModelOutput>{num("a", "1", h.a), num("b", "1", h.b), num("P_eff", "Pa", h.P_eff),
                                                 num("F_BI", "Pa", h.F_BI), num("P", "m", h.depth)};
               }});
  m.push_back({"orphal-anderson",
               "thesis seed 000 eq. 5.3-5.5 (eq. 5.3 with its 2abV term)",
               "strength difference R - Y implied by U = a + b V, its extremum V_m and curvature",
               {req("a", "m/s", "intercept of U = a + b V"), req("b", "1", "slope of U = a + b V"), rho_p, rho_t,
                maybe("V", "m/s", "rod velocity for R - Y (sweep with --velocities)")},
               false,
               [](const ModelArgs& a) {
                 std::vector<ModelOutput> o;
                 append_orphal_anderson_outputs(a.at("a"), a.at("b"), a, o);
                 return o;
               }});
  m.push_back({"orphal-anderson-fit",
               "thesis seed 000 eq. 5.2-5.5",
               "least-squares U = a + b V of --velocities V and --rates U, then eq. 5.3-5.5",
               {rho_p, rho_t},
               true,
               [](const ModelArgs& a) {
                 const LinearFit f = fit_orphal_anderson(a.velocities, a.rates);
                 std::vector<ModelOutput> o{num("a", "m/s", f.a), num("b", "1", f.b), num("r2", "1", f.r2)};
                 append_orphal_anderson_outputs(f.a, f.b, a, o);
                 return o;
               }});
  m.push_back({"pack-evans-fit",
               "thesis seed 000 eq. 6.15-6.16",
               "alpha (and lambda, given a penalty) from an observed depth P and channel radius r",
               {req("P", "m", "observed depth"), opt("r", "m", "channel radius", 0), L, rho_p, rho_t,
                opt("lambda", "1", "particulation factor for alpha", 1), req("sigma_y", "Pa", "target yield strength"),
                V, opt("penalty_outside_root", "1", "1: §6.4 form (default); 0: eq. 3.5 as printed", 1),
                maybe("penalty", "1", "known penalty alpha sigma_y/(rho_p V^2) for the lambda extraction")},
               false,
               [](const ModelArgs& a) {
                 PackEvansObservation ob{a.at("P"),     a.at("r"),       a.at("L"), a.at("lambda"), a.at("rho_p"),
                                         a.at("rho_t"), a.at("sigma_y"), a.at("V"), form_of(a)};
                 std::vector<ModelOutput> o{num("penalty", "1", pack_evans_extract_penalty(ob)),
                                            num("alpha", "1", pack_evans_extract_alpha(ob))};
                 if (a.has("penalty")) o.push_back(num("lambda", "1", pack_evans_extract_lambda(ob, a.at("penalty"))));
                 return o;
               }});
}

/// Every model, in the order `ballista models list` shows them.
std::vector<ModelEntry> make_models() {
  std::vector<ModelEntry> m;
  const CommonParams common = common_params();
  add_steady_jet_models(m, common);
  add_penetrator_variant_models(m, common);
  add_empirical_models(m, common);
  return m;
}

}  // namespace

const std::vector<ModelEntry>& penetration_models() {
  static const std::vector<ModelEntry> models = make_models();
  return models;
}

const ModelEntry& find_penetration_model(const std::string& name) {
  std::string names;
  for (const auto& m : penetration_models()) {
    if (m.name == name) return m;
    names += (names.empty() ? "" : ", ") + m.name;
  }
  throw Error(fmt::format("unknown model '{}'; models: {} (or 'list')", shorten(name), names));
}

std::map<std::string, double> resolve_model_params(const ModelEntry& model,
                                                   const std::map<std::string, double>& given) {
  std::string keys;
  for (const auto& p : model.params) keys += (keys.empty() ? "" : ", ") + p.key;
  for (const auto& [k, v] : given) {
    bool known = false;
    for (const auto& p : model.params) known = known || p.key == k;
    if (!known) throw Error(fmt::format("{}: unknown parameter '{}'; parameters: {}", model.name, shorten(k), keys));
    if (!std::isfinite(v)) throw Error(fmt::format("{}: parameter '{}' = {} is not a finite number", model.name, k, v));
  }
  std::map<std::string, double> out;
  for (const auto& p : model.params) {
    auto it = given.find(p.key);
    if (it != given.end())
      out[p.key] = it->second;
    else if (p.required)
      throw Error(fmt::format("{}: missing parameter '{}' [{}] ({}); give --param {}=VALUE", model.name, p.key, p.unit,
                              p.description, p.key));
    else if (!p.optional_no_default)
      out[p.key] = p.default_value;
  }
  return out;
}

}  // namespace ballista::penetration
