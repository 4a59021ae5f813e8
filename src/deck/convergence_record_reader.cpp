#include "deck/convergence_record_reader.hpp"

#include <cmath>
#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "deck/text_file.hpp"

namespace ballista {

namespace {

constexpr const char* kKey = "convergence_record";

}  // namespace

ConvergenceRecord read_convergence_record(DeckNode& n) {
  namespace fs = std::filesystem;
  ConvergenceRecord r;
  const YAML::Node raw = n.raw(kKey);
  if (!raw.IsDefined() || raw.IsNull()) return r;
  if (!raw.IsScalar()) n.fail(kKey, "expected the path of a grid study's record (a JSON file)");
  fs::path path(raw.Scalar());
  if (path.is_relative()) path = fs::path(n.file()).parent_path() / path;
  path = fs::absolute(path).lexically_normal();
  std::error_code ec;
  if (!fs::exists(path, ec)) n.fail(kKey, "cannot open the grid study's record '" + path.string() + "'");
  const std::string text = read_input_file(path.string(), n.child_path(kKey), "the grid study's record");
  n.set_resolved(kKey, YAML::Node(path.string()));
  r.path = path.string();
  const auto bad = [&](const std::string& what) {
    n.fail(kKey, "the grid study's record '" + path.string() + "': " + what);
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
  return r;
}

}  // namespace ballista
