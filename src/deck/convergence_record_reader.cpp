#include "deck/convergence_record_reader.hpp"

#include <cmath>

#include <yaml-cpp/yaml.h>

#include "deck/shape_file.hpp"
#include "deck/text_file.hpp"

namespace ballista {

namespace {

constexpr const char* kKey = "convergence_record";

}  // namespace

ConvergenceRecord read_convergence_record(DeckNode& n) {
  ConvergenceRecord r;
  if (!n.has(kKey)) return r;
  const std::string path = deck_file(n, kKey, "grid study's record");
  const std::string text = read_input_file(path, n.child_path(kKey), "the grid study's record");
  r.path = path;
  const auto bad = [&](const std::string& what) {
    n.fail(kKey, "the grid study's record '" + path + "': " + what);
  };
  YAML::Node doc;
  try {
    doc = YAML::Load(text);  // JSON is YAML
  } catch (const YAML::Exception& e) {
    bad(std::string("not JSON: ") + e.what());
  }
  if (!doc.IsMap() || !doc["physics_fingerprint"] || !doc["quantities"] || !doc["quantities"].IsMap())
    bad("expected an object with physics_fingerprint and quantities");
  r.fingerprint = doc["physics_fingerprint"].as<std::string>();
  r.study = doc["study"] ? doc["study"].as<std::string>() : std::string();
  for (const auto& q : doc["quantities"]) {
    ConvergenceRecord::Quantity out;
    out.name = q.first.as<std::string>();
    const YAML::Node& v = q.second;
    if (!v.IsMap() || !v["summary_key"] || !v["richardson"] || !v["levels"] || !v["levels"].IsSequence())
      bad("quantity '" + out.name + "' needs summary_key, richardson and levels");
    out.label = v["label"] ? v["label"].as<std::string>() : out.name;
    out.summary_key = v["summary_key"].as<std::string>();
    try {
      // null: the study found no estimate (the quantity did not converge).
      out.richardson = v["richardson"].IsNull() ? NAN : v["richardson"].as<double>();
      out.order = v["order"] && !v["order"].IsNull() ? v["order"].as<double>() : NAN;
      for (const auto& l : v["levels"]) {
        if (!l.IsSequence() || l.size() != 2) bad("quantity '" + out.name + "': a level is [cell, value]");
        out.levels.emplace_back(l[0].as<double>(), l[1].as<double>());
      }
    } catch (const YAML::Exception& e) {
      bad("quantity '" + out.name + "': " + e.what());
    }
    if (!v["richardson"].IsNull() && !(std::isfinite(out.richardson) && out.richardson != 0.0))
      bad("quantity '" + out.name + "': richardson must be a finite, non-zero number, or null (not converged)");
    r.quantities.push_back(std::move(out));
  }
  if (const YAML::Node& checked = doc["checked"]) {
    if (!checked.IsMap()) bad("'checked' is an object of configurations by name");
    for (const auto& c : checked) {
      ConvergenceRecord::Checked out;
      out.name = c.first.as<std::string>();
      const YAML::Node& v = c.second;
      if (!v.IsMap() || !v["configuration_fingerprint"] || !v["values"] || !v["values"].IsMap())
        bad("checked configuration '" + out.name + "' needs configuration_fingerprint and values");
      try {
        out.label = v["label"] ? v["label"].as<std::string>() : out.name;
        out.fingerprint = v["configuration_fingerprint"].as<std::string>();
      } catch (const YAML::Exception& e) {
        bad("checked configuration '" + out.name + "': " + e.what());
      }
      for (const ConvergenceRecord::Checked& other : r.checked)
        if (other.fingerprint == out.fingerprint)
          bad("checked configurations '" + other.name + "' and '" + out.name +
              "' have one fingerprint: one run is one configuration");
      for (const auto& q : v["values"]) {
        const std::string name = q.first.as<std::string>();
        bool known = false;
        for (const ConvergenceRecord::Quantity& rq : r.quantities) known = known || rq.name == name;
        if (!known) bad("checked configuration '" + out.name + "': '" + name + "' is not a quantity of the record");
        try {
          out.values.emplace_back(name, q.second.as<double>());
        } catch (const YAML::Exception& e) {
          bad("checked configuration '" + out.name + "': '" + name + "': " + e.what());
        }
      }
      r.checked.push_back(std::move(out));
    }
  }
  return r;
}

}  // namespace ballista
