#include "penetration/models_cli.hpp"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <map>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/summary_writer.hpp"
#include "penetration/model_catalog.hpp"

namespace ballista::penetration {

namespace {

std::string quote(const std::string& s) {
  std::string out;
  json_escape_to(out, s);  // the run summary's escaping (io/summary_writer)
  return out;
}
std::string number(double x) {
  return std::isfinite(x) ? fmt::format("{}", x) : "null";
}

void print_list() {
  for (const ModelEntry& m : penetration_models()) {
    std::cout << m.name << "  (" << m.equations << ")\n    " << m.description << "\n";
    if (m.uses_series)
      std::cout << fmt::format("      {:<22} [{}] {}\n", "--velocities", "m/s", "impact velocities V (series)")
                << fmt::format("      {:<22} [{}] {}\n", "--rates", "m/s", "penetration velocities U (series)");
    for (const ModelParam& p : m.params) {
      const std::string when = p.required              ? "required"
                               : p.optional_no_default ? "optional"
                                                       : fmt::format("default {:g}", p.default_value);
      std::cout << fmt::format("      {:<22} [{}] {}; {}\n", p.key, p.unit, p.description, when);
    }
  }
}

bool has_param(const ModelEntry& m, const std::string& key) {
  for (const auto& p : m.params)
    if (p.key == key) return true;
  return false;
}

}  // namespace

std::vector<std::pair<std::string, double>> parse_model_params(const std::vector<std::string>& params) {
  std::vector<std::pair<std::string, double>> out;
  for (const std::string& s : params) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error(fmt::format("--param '{}': expected key=value (for instance --param rho_p=17600)", shorten(s)));
    const std::string key = s.substr(0, eq), text = s.substr(eq + 1);
    size_t used = 0;
    double v = 0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size())
      throw Error(fmt::format("--param '{}': value '{}' of '{}' is not a number (SI units, e.g. 1.5e9)", shorten(s),
                              shorten(text), shorten(key)));
    if (!std::isfinite(v))
      throw Error(fmt::format("--param '{}': {} must be a finite number", shorten(s), shorten(key)));
    out.emplace_back(key, v);
  }
  return out;
}

int run_models_cli(const ModelsCliOptions& o) {
  if (o.model == "list") {
    if (!o.params.empty() || !o.velocities.empty() || !o.rates.empty())
      throw Error("models list takes no --param, --velocities or --rates");
    print_list();
    return 0;
  }
  const ModelEntry& m = find_penetration_model(o.model);
  std::map<std::string, double> given;
  for (const auto& [k, v] : parse_model_params(o.params)) {
    if (given.count(k)) throw Error(fmt::format("--param {}: given twice", shorten(k)));
    given[k] = v;
  }
  ModelArgs args;
  std::vector<std::map<std::string, double>> cases;  // one evaluation per sweep velocity
  if (m.uses_series) {
    if (o.velocities.empty() || o.rates.empty())
      throw Error(fmt::format("{}: needs --velocities V1,V2,... and --rates U1,U2,... [m/s]", m.name));
    args.velocities = o.velocities;
    args.rates = o.rates;
    cases.push_back(resolve_model_params(m, given));
  } else {
    if (!o.rates.empty()) throw Error(fmt::format("--rates: model {} takes no series (only the fit models)", m.name));
    if (!o.velocities.empty()) {
      if (!has_param(m, "V")) throw Error(fmt::format("--velocities: model {} has no parameter V", m.name));
      if (given.count("V")) throw Error("--velocities and --param V=...: give one of them");
      for (double v : o.velocities) {
        auto g = given;
        g["V"] = v;
        cases.push_back(resolve_model_params(m, g));
      }
    } else {
      cases.push_back(resolve_model_params(m, given));
    }
  }

  std::vector<std::vector<ModelOutput>> rows;
  for (const auto& c : cases) {
    args.params = c;
    try {
      rows.push_back(m.evaluate(args));
      // A result that is not a number is an error, never a success (overflow of extreme inputs).
      for (const ModelOutput& out : rows.back())
        if (out.text.empty() && !std::isfinite(out.value)) {
          std::string params;
          for (const auto& [k, v] : c) params += fmt::format("{}{}={:g}", params.empty() ? "" : ", ", k, v);
          throw Error(fmt::format("{}: result {} is {} (not a finite number) for {}: the inputs are outside the "
                                  "range where the model can be evaluated in double precision",
                                  m.name, out.key, out.value, params));
        }
    } catch (const Error& e) {
      if (cases.size() > 1) throw Error(fmt::format("V = {:g} m/s: {}", c.at("V"), e.what()));
      throw;
    }
  }

  std::cout << m.name << " (" << m.equations << ")\n";
  for (size_t i = 0; i < rows.size(); ++i) {
    if (cases.size() > 1) std::cout << fmt::format("V = {:g} m/s\n", cases[i].at("V"));
    for (const ModelOutput& out : rows[i]) {
      if (!out.text.empty())
        std::cout << fmt::format("  {:<18} {}\n", out.key, out.text);
      else
        std::cout << fmt::format("  {:<18} {:.8g} {}\n", out.key, out.value, out.unit);
    }
  }

  if (!o.json_path.empty()) {
    std::string j = "{\n  \"model\": " + quote(m.name) + ",\n  \"equations\": " + quote(m.equations) + ",\n";
    j += "  \"units\": {";
    bool first = true;
    for (const auto& p : m.params) {
      j += std::string(first ? "" : ", ") + quote(p.key) + ": " + quote(p.unit);
      first = false;
    }
    if (!rows.empty())
      for (const auto& out : rows[0]) j += std::string(first ? "" : ", ") + quote(out.key) + ": " + quote(out.unit);
    j += "},\n  \"results\": [\n";
    for (size_t i = 0; i < rows.size(); ++i) {
      j += "    {\"params\": {";
      bool f = true;
      for (const auto& [k, v] : cases[i]) {
        j += std::string(f ? "" : ", ") + quote(k) + ": " + number(v);
        f = false;
      }
      j += "}, \"outputs\": {";
      f = true;
      for (const auto& out : rows[i]) {
        j += std::string(f ? "" : ", ") + quote(out.key) + ": " +
             (out.text.empty() ? number(out.value) : quote(out.text));
        f = false;
      }
      j += std::string("}}") + (i + 1 < rows.size() ? "," : "") + "\n";
    }
    if (m.uses_series) {
      j += "  ],\n  \"series\": {\"V\": [";
      for (size_t i = 0; i < o.velocities.size(); ++i) j += (i ? ", " : "") + number(o.velocities[i]);
      j += "], \"U\": [";
      for (size_t i = 0; i < o.rates.size(); ++i) j += (i ? ", " : "") + number(o.rates[i]);
      j += "]}\n}\n";
    } else {
      j += "  ]\n}\n";
    }
    write_file_atomic(o.json_path, j);
  }
  return 0;
}

}  // namespace ballista::penetration
