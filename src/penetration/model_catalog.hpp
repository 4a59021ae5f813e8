#pragma once
// The analytic penetration models as a table the command line (`ballista models`) lists and
// evaluates by name: parameters with units and ranges in words, outputs with units. SI units.
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace ballista::penetration {

struct ModelParam {
  std::string key;
  std::string unit;
  std::string description;
  bool required = true;
  double default_value = 0;          ///< used when not required and not given (unless optional_no_default)
  bool optional_no_default = false;  ///< not required and absent means "not given" (outputs that need it are skipped)
};

/// One output of an evaluation: a number with a unit, or a word (text non-empty).
struct ModelOutput {
  std::string key;
  std::string unit;
  double value = 0;
  std::string text;
};

struct ModelArgs {
  std::map<std::string, double> params;  ///< resolved: every required and defaulted key present
  std::vector<double> velocities;        ///< series V [m/s] (fit models)
  std::vector<double> rates;             ///< series U [m/s] (fit models)
  bool has(const std::string& key) const { return params.count(key) > 0; }
  double at(const std::string& key) const { return params.at(key); }
};

struct ModelEntry {
  std::string name;
  std::string equations;  ///< e.g. "thesis seed 000 eq. 3.1-3.2"
  std::string description;
  std::vector<ModelParam> params;
  bool uses_series = false;  ///< reads ModelArgs::velocities and rates instead of a scalar V
  std::function<std::vector<ModelOutput>(const ModelArgs&)> evaluate;
};

/// Every model, in the order of the thesis.
const std::vector<ModelEntry>& penetration_models();

/// The model called `name`; throws ballista::Error listing the valid names.
const ModelEntry& find_penetration_model(const std::string& name);

/// Checks the given keys against the model (unknown key, missing required key: Error naming it
/// and listing the valid ones) and fills defaults.
std::map<std::string, double> resolve_model_params(const ModelEntry& model, const std::map<std::string, double>& given);

}  // namespace ballista::penetration
