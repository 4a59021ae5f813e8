#include "run/headlines.hpp"

#include <cmath>

#include <fmt/format.h>

#include "analysis/convergence_statement.hpp"

namespace ballista {

namespace {

/// A finite number at `key` of an object, else NaN (absent, null, or not a number).
double number_at(const JsonValue& obj, const std::string& key) {
  if (obj.kind() != JsonValue::Kind::Object || !obj.contains(key)) return NAN;
  const JsonValue& v = obj.at(key);
  if (v.kind() != JsonValue::Kind::Number && v.kind() != JsonValue::Kind::Int) return NAN;
  return v.as_number();
}

// A headline names the points holding the step when one body's points set at least this share of
// at least kStepHeldSamples samples, are at most one in kFewStepPointsPer of the run's points (and
// all counted: the tally remembers kStepTallyMaxIds), and the step without the fastest thousandth
// of the points would have been at least kStepHeldMargin times larger on average at those samples
// (StepLimiter::margin: MPM on one rank).
constexpr double kStepHeldShare = 0.5;
constexpr double kStepHeldSamples = 8;
constexpr double kFewStepPointsPer = 1000;
constexpr double kStepHeldMargin = 1.2;

std::string mm(double metres) { return std::isfinite(metres) ? fmt::format("{:.1f} mm", metres * 1e3) : "n/a"; }

/// Each recorded quantity's gap from converged at a level or checked configuration, for a headline
/// ("tunnel depth -3.5 % (129.4 mm converged), casing hole not run at this level"); `where` names
/// the level or configuration for a quantity it did not measure. Sets `unmeasured` if one was not.
std::string quantity_gaps(const JsonValue& qs, const std::string& where, bool& unmeasured) {
  std::string gaps;
  for (const std::string& name : qs.keys()) {
    const JsonValue& q = qs.at(name);
    const double gap = number_at(q, "level_gap");
    const std::string sep = gaps.empty() ? "" : ", ";
    if (q.contains("converged_in_study") && !q.at("converged_in_study").as_bool()) {
      const double order = number_at(q, "order");
      gaps += fmt::format("{}{} not converged in the study{}", sep, q.at("label").as_string(),
                          std::isfinite(order) ? fmt::format(" (observed order {:.2f})", order) : "");
    } else if (!std::isfinite(gap)) {
      gaps += fmt::format("{}{} not run {}", sep, q.at("label").as_string(), where);
      unmeasured = true;
    } else {
      gaps += fmt::format("{}{} {:+.1f} % ({} converged)", sep, q.at("label").as_string(), 100.0 * gap,
                          mm(number_at(q, "richardson")));
    }
  }
  return gaps;
}

/// The level of the deck's grid study this run is, or the configuration the study checked, and how
/// far it is from converged (analysis/convergence_statement.hpp), or why that is not known; only for
/// a completed run (an unfinished run's depth is no level's answer). Returns whether the study has
/// said how far this run is (a level or a checked configuration).
bool study_lines(const JsonValue& p, bool completed, std::vector<std::string>& out) {
  const JsonValue* study = p.contains("convergence") ? &p.at("convergence") : nullptr;
  if (!study || !completed) return false;
  const double level = number_at(*study, "level_cell");
  const bool checked = study->contains("checked") && study->at("checked").kind() == JsonValue::Kind::Object;
  if (std::isfinite(level) || checked) {
    const double within = number_at(*study, "within");
    const bool all_converged = !study->contains("all_converged") || study->at("all_converged").as_bool();
    bool unmeasured = false;  // a quantity the study did not run at this level: no claim for it
    const std::string gaps = quantity_gaps(study->at("quantities"),
                                           checked ? "in this configuration" : "at this level", unmeasured);
    const bool converged = within <= kConvergedWithin && all_converged && !unmeasured;
    const std::string what =
        checked ? fmt::format("the configuration '{}' its grid study checked",
                              study->at("checked").at("label").as_string())
                : fmt::format("the {:g} mm level of the deck's grid study", level * 1e3);
    out.push_back(fmt::format("{}: this is {}, where it was {} ({})",
                              converged ? fmt::format("CONVERGED WITHIN {:g} %", 100 * kConvergedWithin)
                                        : std::string("NOT CONVERGED"),
                              what, gaps, study->at("record").as_string()));
    return true;
  }
  out.push_back(study->at("fingerprint_matches").as_bool()
                    ? fmt::format("NOT CONVERGED?: this run's cells are not a level of the deck's grid study ({}): "
                                  "how far it is from converged is not known",
                                  study->at("record").as_string())
                    : fmt::format("NOT CONVERGED?: the deck's grid study ({}) is of other physics than this run: "
                                  "how far it is from converged is not known (validation/perforation_convergence.py)",
                                  study->at("record").as_string()));
  return false;
}

/// `completed`: the run reached its end (not failed, not interrupted): only then is a depth final
/// or known to be the depth at end_time.
void penetration_lines(const JsonValue& p, bool completed, std::vector<std::string>& out) {
  const std::string target = p.contains("target") ? p.at("target").as_string() : "the target";
  // Penetrator points far beyond the tunnel's end (analysis/beyond_tunnel.hpp) make the deepest
  // point no depth of penetration: the tunnel's end is then the depth, and the stray points are named.
  const JsonValue* beyond = p.contains("beyond_tunnel") ? &p.at("beyond_tunnel") : nullptr;
  const double strays = beyond ? number_at(*beyond, "points") : NAN;
  if (std::isfinite(strays) && strays > 0)
    out.push_back(fmt::format("depth into '{}' = {} (the tunnel's end; the deepest penetrator point, {}, is one of {:g} "
                              "({:.2g} % of its mass) beyond it in rock nothing has opened)",
                              target, mm(number_at(*beyond, "tunnel_end")), mm(number_at(p, "final_depth")), strays,
                              100.0 * number_at(*beyond, "mass_share")));
  else
    out.push_back(fmt::format("depth into '{}' = {} (cavity {})", target, mm(number_at(p, "final_depth")),
                              mm(number_at(p, "final_cavity_depth"))));
  if (p.contains("holes") && p.at("holes").kind() == JsonValue::Kind::Object) {
    const JsonValue& holes = p.at("holes");
    for (const std::string& plate : holes.keys()) {
      const JsonValue& h = holes.at(plate);
      const bool perforated = h.contains("perforated") && h.at("perforated").as_bool();
      out.push_back(perforated ? fmt::format("hole in '{}': entrance diameter {}, narrowest {}", plate,
                                             mm(number_at(h, "entrance_diameter")), mm(number_at(h, "min_diameter")))
                               : fmt::format("'{}' not perforated", plate));
    }
  }
  if (p.contains("tunnel")) {
    const double d = number_at(p.at("tunnel"), "entrance_diameter");
    if (std::isfinite(d)) out.push_back(fmt::format("tunnel entrance diameter {}", mm(d)));
  }
  // Whether the depth is final: a depth read while the penetrator still moves is one at end_time
  // (or, through a perforated target, no depth at all).
  const bool ended_spent = p.contains("end_when_spent") && std::isfinite(number_at(p.at("end_when_spent"), "time"));
  if (completed && ended_spent)
    out.push_back(fmt::format("the penetrator was spent {:.1f} us after firing (kinetic energy at most {:g} of its peak): "
                              "the depth is final",
                              number_at(p.at("end_when_spent"), "time") * 1e6, number_at(p.at("end_when_spent"), "share")));
  else if (completed && p.contains("stop_time") && p.at("stop_time").kind() == JsonValue::Kind::Null &&
           std::isfinite(number_at(p, "final_depth")) && number_at(p, "final_depth") > 0.0)
    out.push_back(
        "STILL MOVING at the end of the run: the depth is the depth at end_time, not a final one (a longer "
        "simulation.end_time, with penetration.end_when_spent to stop once the penetrator is spent, or a longer "
        "target if it was perforated)");
  const bool study_said = study_lines(p, completed, out);
  const double cells = number_at(p, "cells_across_radius");
  const double coarser = p.contains("path_cells") ? number_at(p.at("path_cells"), "coarser_from_depth") : NAN;
  const bool unresolved = p.contains("resolved") && !p.at("resolved").as_bool();
  if (unresolved && std::isfinite(coarser))
    out.push_back(fmt::format(
        "NOT CONVERGED: the finest cells along the line of flight end {} deep and the tunnel runs on to {} in "
        "cells up to {}: its end is not at the resolution of the cells across the penetrator (extend grid.refine "
        "along the flight)",
        mm(coarser), mm(number_at(p.at("tunnel"), "depth")), mm(number_at(p.at("path_cells"), "coarsest"))));
  else if (unresolved && std::isfinite(cells) && !study_said)  // else the study has said how far
    out.push_back(fmt::format(
        "NOT CONVERGED: the penetrator is {:.3g} cells across its radius; depth and rate are not converged "
        "at this resolution (docs/validation.md)",
        cells));
  else if (p.contains("formed_jet") && !study_said)
    out.push_back(
        "CONVERGENCE NOT KNOWN: the jet formed in this run, so its cells across the radius were not known before "
        "it; only a grid study of this deck says how far its depth and holes are from converged "
        "(docs/penetration.md, \"A jet formed in the run\")");
}

/// A few points holding the stable step for most of the run (run/step_tally.hpp): the run's cost
/// is theirs, and what they are (a body, a signal, J) is where to look.
void step_lines(const JsonValue& summary, std::vector<std::string>& out) {
  if (!summary.contains("statistics")) return;
  const JsonValue& st = summary.at("statistics");
  if (!st.contains("step_set_by")) return;
  const JsonValue& tally = st.at("step_set_by");
  if (!tally.contains("entries") || tally.at("entries").size() == 0) return;
  const JsonValue& top = tally.at("entries").at(std::size_t{0});
  const double share = number_at(top, "share"), points = number_at(top, "points");
  const double particles = number_at(st, "particles"), margin = number_at(top, "margin_mean");
  const bool few = !top.at("points_at_least").as_bool() && points * kFewStepPointsPer <= particles;
  if (!(share >= kStepHeldShare) || !(number_at(tally, "samples") >= kStepHeldSamples) || !few ||
      !(margin >= kStepHeldMargin))
    return;
  const bool viscous = top.at("signal").as_string() == "bulk_viscosity";
  out.push_back(fmt::format(
      "STEP HELD BY {:.0f} POINT{}: {:.0f} % of the sampled steps were set by {:.0f} point{} of '{}' ({} up to {:.3g} m/s, "
      "J {:.3g} to {:.3g}); without the fastest thousandth of the points the step would have been {:.2g}x larger "
      "there on average (summary.json statistics.step_set_by)",
      points, points == 1 ? "" : "S", 100.0 * share, points, points == 1 ? "" : "s", top.at("body").as_string(),
      viscous ? "bulk-viscosity signal" : "wave speed", number_at(top, "signal_speed_max"), number_at(top, "J_min"),
      number_at(top, "J_max"), margin));
}

}  // namespace

std::vector<std::string> headline_lines(const JsonValue& summary) {
  std::vector<std::string> out;
  const bool completed = summary.contains("status") && summary.at("status").kind() == JsonValue::Kind::String &&
                         summary.at("status").as_string() == "completed";
  if (summary.contains("penetration")) penetration_lines(summary.at("penetration"), completed, out);
  if (summary.contains("tension") && summary.at("tension").kind() == JsonValue::Kind::Object) {
    // Points beyond their material's cohesive limit (run/tension_watch.hpp): the answer above
    // includes a tension no solid of that material holds.
    const JsonValue& t = summary.at("tension");
    for (const std::string& material : t.keys()) {
      const JsonValue& m = t.at(material);
      const double n = number_at(m, "most_points_beyond");
      if (!(n > 0)) continue;
      out.push_back(fmt::format(
          "UNPHYSICAL TENSION: up to {:.0f} points of '{}' beyond its cohesive limit of {:.3g} GPa (down to {:.3g} GPa "
          "at {:.3g} us): the results near them are not physical (summary.json \"tension\"; eos.min_pressure caps it)",
          n, material, number_at(m, "cohesive_limit") * 1e-9, number_at(m, "most_tensile_pressure") * 1e-9,
          number_at(m, "most_tensile_time") * 1e6));
    }
  }
  step_lines(summary, out);
  if (summary.contains("fragments")) {
    const JsonValue& f = summary.at("fragments");
    const double n = number_at(f, "count");
    if (std::isfinite(n))
      out.push_back(fmt::format("fragments: {:.0f}, largest {:.4g} kg, mean {:.4g} kg", n, number_at(f, "largest_mass"),
                                number_at(f, "mean_mass")));
    if (f.contains("above_min_mass")) {
      const JsonValue& a = f.at("above_min_mass");
      out.push_back(fmt::format("fragments of at least {:.4g} kg: {:.0f}, mean {:.4g} kg, Mott mu {:.4g} kg",
                                number_at(a, "min_mass"), number_at(a, "count"), number_at(a, "mean_mass"),
                                number_at(a, "mott_mu")));
    }
  }
  return out;
}

}  // namespace ballista
