// model_list and model_evaluate: the analytic penetration models of `ballista models`
// (penetration/model_catalog.hpp), with the same checks of the parameters and of the results.
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "core/error.hpp"
#include "penetration/model_catalog.hpp"

namespace py = pybind11;

namespace ballista::python {

namespace {

using penetration::ModelEntry;

py::list model_list() {
  py::list models;
  for (const ModelEntry& m : penetration::penetration_models()) {
    py::list params;
    for (const auto& p : m.params) {
      py::dict d;
      d["key"] = p.key;
      d["unit"] = p.unit;
      d["description"] = p.description;
      d["required"] = p.required;
      d["default"] = p.required || p.optional_no_default ? py::none() : py::cast(p.default_value);
      params.append(d);
    }
    py::dict d;
    d["name"] = m.name;
    d["equations"] = m.equations;
    d["description"] = m.description;
    d["uses_series"] = m.uses_series;
    d["params"] = params;
    models.append(d);
  }
  return models;
}

py::list model_evaluate(const std::string& name, const std::map<std::string, double>& given,
                        const std::vector<double>& velocities, const std::vector<double>& rates) {
  const ModelEntry& m = penetration::find_penetration_model(name);
  if (m.uses_series && (velocities.empty() || rates.empty()))
    throw Error(fmt::format("{}: needs the series velocities and rates [m/s]", m.name));
  if (!m.uses_series && (!velocities.empty() || !rates.empty()))
    throw Error(fmt::format("{}: takes no series (only the fit models do); give V as a parameter", m.name));
  penetration::ModelArgs args;
  args.params = penetration::resolve_model_params(m, given);
  args.velocities = velocities;
  args.rates = rates;
  py::list out;
  for (const penetration::ModelOutput& o : m.evaluate(args)) {
    // A result that is not a number is an error, never a success (as `ballista models`).
    if (o.text.empty() && !std::isfinite(o.value))
      throw Error(fmt::format("{}: result {} is {} (not a finite number): the inputs are outside the range where "
                              "the model can be evaluated in double precision",
                              m.name, o.key, o.value));
    py::dict d;
    d["key"] = o.key;
    d["unit"] = o.unit;
    d["value"] = o.text.empty() ? py::cast(o.value) : py::cast(o.text);
    out.append(d);
  }
  return out;
}

}  // namespace

void bind_models(py::module_& m) {
  m.def("model_list", &model_list, "Every analytic penetration model with its parameters (SI units).");
  m.def("model_evaluate", &model_evaluate, py::arg("name"), py::arg("params"), py::arg("velocities"),
        py::arg("rates"), "Evaluates one model; returns its outputs (key, unit, value).");
}

}  // namespace ballista::python
