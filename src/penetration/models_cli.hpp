#pragma once
// `ballista models list` and `ballista models NAME --param key=value ... [--velocities ...]
// [--json FILE]`: evaluates the analytic penetration models of model_catalog.hpp
// (docs/penetration_models.md).
#include <string>
#include <vector>

namespace ballista::penetration {

struct ModelsCliOptions {
  std::string model;                ///< "list" or a model name
  std::vector<std::string> params;  ///< "key=value" (SI units)
  std::vector<double> velocities;   ///< sweep of V [m/s], or the V series of a fit
  std::vector<double> rates;        ///< U series of a fit [m/s]
  std::string json_path;            ///< also write the results as JSON here (empty: no)
};

/// Prints the model list or one model's results to stdout; throws ballista::Error on bad input.
int run_models_cli(const ModelsCliOptions& options);

/// Parses "key=value" options into numbers; throws Error naming the bad option.
std::vector<std::pair<std::string, double>> parse_model_params(const std::vector<std::string>& params);

}  // namespace ballista::penetration
