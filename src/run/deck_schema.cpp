#include "run/deck_schema.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "core/data_dir.hpp"
#include "deck/deck_reader.hpp"
#include "deck/schema_recorder.hpp"
#include "io/summary_writer.hpp"
#include "materials/material.hpp"
#include "points/probe_registry.hpp"
#include "points/solver_registry.hpp"

namespace ballista {

namespace {

/// The keys below one pattern: named children, list items ("[]"), user-named entries ("*").
struct SchemaNode {
  std::vector<SchemaKey> kinds;
  std::map<std::string, SchemaNode> children;
  std::unique_ptr<SchemaNode> items, entries;

  SchemaNode& at(const std::string& segment) {
    if (segment == "[]") {
      if (!items) items = std::make_unique<SchemaNode>();
      return *items;
    }
    if (segment == "*") {
      if (!entries) entries = std::make_unique<SchemaNode>();
      return *entries;
    }
    return children[segment];
  }
  void add(const SchemaKey& k) { add_schema_key(kinds, k); }
};

/// "bodies[].shape.radius" -> bodies, [], shape, radius; "materials.*.eos.type" -> materials, *, eos, type.
std::vector<std::string> segments(const std::string& pattern) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern.compare(i, 2, "[]") == 0) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
      out.push_back("[]");
      ++i;
    } else if (pattern[i] == '.') {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
    } else {
      cur += pattern[i];
    }
  }
  if (!cur.empty()) out.push_back(cur);
  return out;
}

SchemaNode& node_at(SchemaNode& root, const std::string& pattern) {
  SchemaNode* n = &root;
  for (const std::string& s : segments(pattern)) n = &n->at(s);
  return *n;
}

/// A parameter of the registries as the readers would report it.
SchemaKey key_of_param(const ParamSpec& p) {
  SchemaKey k;
  if (!p.choices.empty()) {
    k.kind = SchemaKey::Kind::Choice;
    k.choices = p.choices;
    k.fallback = p.default_choice;
    return k;
  }
  k.kind = p.integer ? SchemaKey::Kind::Integer : SchemaKey::Kind::Number;
  k.range = NumberRange{p.min, p.max, p.min_exclusive, p.max_exclusive, p.unit};
  k.required = p.required;
  if (!p.required && std::isfinite(p.default_value)) k.fallback = format_number(p.default_value);
  return k;
}

SchemaKey key_of_probe_param(const ProbeParam& p) {
  SchemaKey k;
  switch (p.kind) {
    case ProbeParam::Kind::Body: k.kind = SchemaKey::Kind::String; break;
    case ProbeParam::Kind::Axis:
      k.kind = SchemaKey::Kind::Choice;
      k.choices = {"x", "y", "z"};
      break;
    case ProbeParam::Kind::Number:
      k.kind = SchemaKey::Kind::Number;
      k.range = NumberRange{p.min, std::numeric_limits<double>::infinity(), p.min_exclusive, false, p.unit};
      break;
    case ProbeParam::Kind::Vector:
      k.kind = SchemaKey::Kind::Vector;
      k.min_items = 2;
      k.range.unit = p.unit;
      break;
    case ProbeParam::Kind::Word:
      k.kind = p.choices.empty() ? SchemaKey::Kind::String : SchemaKey::Kind::Choice;
      k.choices = p.choices;
      break;
  }
  k.required = p.required;
  return k;
}

/// The registries' parameters, so that a key no example uses still completes: every material
/// model's (its dotted names are sub-maps: eos.type), every solver's section, every probe kind's.
void add_registries(SchemaNode& root) {
  SchemaNode& material = node_at(root, "materials.*");
  SchemaKey model;
  model.kind = SchemaKey::Kind::Choice;
  for (const MaterialFactory& f : material_registry()) {
    model.choices.push_back(f.model);
    for (const ParamSpec& p : f.params) node_at(material, p.name).add(key_of_param(p));
  }
  material.children["model"].kinds.clear();
  material.children["model"].add(model);
  for (const SolverFactory& f : solver_registry()) {
    if (f.section.empty()) continue;
    SchemaNode& section = node_at(root, f.section);
    for (const ParamSpec& p : f.params) node_at(section, p.name).add(key_of_param(p));
  }
  SchemaNode& probe = node_at(root, "probes[]");
  SchemaKey type;
  type.kind = SchemaKey::Kind::Choice;
  for (const ProbeFactory& f : probe_registry()) {
    type.choices.push_back(f.name);
    for (const ProbeParam& p : f.params) node_at(probe, p.name).add(key_of_probe_param(p));
  }
  probe.children["type"].kinds.clear();
  probe.children["type"].add(type);
}

/// "kg/m^3; default 8930; required" for a key's description.
std::string describe(const SchemaKey& k) {
  std::string d;
  auto add = [&](const std::string& s) { d += (d.empty() ? "" : "; ") + s; };
  if (!k.range.unit.empty() && k.range.unit != "-") add("unit " + k.range.unit);
  if (k.required) add("required");
  if (!k.fallback.empty()) add("default " + k.fallback);
  return d;
}

JsonValue leaf(const SchemaKey& k) {
  JsonValue j = JsonValue::object();
  auto bounds = [&](const NumberRange& r) {
    // Integer ranges arrive as whole longs; bounds beyond double's exact integers say nothing.
    if (std::isfinite(r.min) && std::abs(r.min) < 1e15) j[r.min_exclusive ? "exclusiveMinimum" : "minimum"] = r.min;
    if (std::isfinite(r.max) && std::abs(r.max) < 1e15) j[r.max_exclusive ? "exclusiveMaximum" : "maximum"] = r.max;
  };
  switch (k.kind) {
    case SchemaKey::Kind::Any: break;
    case SchemaKey::Kind::Number:
      j["type"] = "number";
      bounds(k.range);
      break;
    case SchemaKey::Kind::Integer:
      j["type"] = "integer";
      bounds(k.range);
      break;
    case SchemaKey::Kind::Boolean: j["type"] = "boolean"; break;
    case SchemaKey::Kind::String: j["type"] = "string"; break;
    case SchemaKey::Kind::Choice: {
      // A choice spelled as a whole number (mpm.multirate: 8) is read by YAML as one; the deck
      // reader takes it as the name, so the schema takes both spellings.
      JsonValue e = JsonValue::array();
      for (const std::string& c : k.choices) e.push_back(JsonValue(c));
      for (const std::string& c : k.choices)
        if (!c.empty() && c.find_first_not_of("0123456789") == std::string::npos && c.size() < 10)
          e.push_back(JsonValue(std::stol(c)));
      j["enum"] = e;
      break;
    }
    case SchemaKey::Kind::Vector:
      j["type"] = "array";
      j["items"]["type"] = "number";
      j["minItems"] = k.min_items;
      j["maxItems"] = 3;
      break;
    case SchemaKey::Kind::Strings:
      j["type"] = "array";
      j["items"]["type"] = "string";
      break;
    case SchemaKey::Kind::Object:
    case SchemaKey::Kind::Names: j["type"] = "object"; break;
    case SchemaKey::Kind::List: j["type"] = "array"; break;
  }
  if (const std::string d = describe(k); !d.empty()) j["description"] = d;
  return j;
}

JsonValue emit(const SchemaNode& n) {
  if (!n.children.empty() || n.entries) {
    JsonValue j = JsonValue::object();
    j["type"] = "object";
    if (!n.children.empty()) {
      JsonValue& props = j["properties"];
      for (const auto& [name, child] : n.children) props[name] = emit(child);
    }
    if (n.entries) j["additionalProperties"] = emit(*n.entries);
    return j;
  }
  if (n.items) {
    JsonValue j = JsonValue::object();
    j["type"] = "array";
    j["items"] = emit(*n.items);
    return j;
  }
  if (n.kinds.size() == 1) return leaf(n.kinds.front());
  JsonValue any = JsonValue::object();
  for (const SchemaKey& k : n.kinds) any["anyOf"].push_back(leaf(k));
  return any;
}

}  // namespace

std::string deck_schema(const std::vector<std::string>& decks) {
  SchemaRecorder recorder;
  {
    const SchemaRecording recording(recorder);
    for (const std::string& d : decks) (void)read_deck(d);
  }
  SchemaNode root;
  for (const auto& [pattern, kinds] : recorder.keys())
    for (const SchemaKey& k : kinds) node_at(root, pattern).add(k);
  add_registries(root);
  JsonValue schema = emit(root);
  JsonValue out = JsonValue::object();
  out["$schema"] = "https://json-schema.org/draft/2020-12/schema";
  out["title"] = "Ballista run deck";
  out["description"] =
      "The keys of a Ballista run deck (docs/deck.md), SI units. Made by `ballista schema` from the deck readers "
      "and the registries; a key it does not list is not refused by it (`ballista run` checks every key).";
  for (const std::string& k : schema.keys()) out[k] = schema.at(k);
  return out.dump(1) + "\n";
}

std::vector<std::string> example_run_decks() {
  namespace fs = std::filesystem;
  std::vector<std::string> decks;
  const fs::path dir = fs::path(data_dir()) / "examples";
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".yaml" && name.rfind("drive_", 0) != 0) decks.push_back(e.path().string());
  }
  std::sort(decks.begin(), decks.end());
  return decks;
}

}  // namespace ballista
