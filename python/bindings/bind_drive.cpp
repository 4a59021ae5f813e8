// drive_deck: one material point driven by a drive deck's program (`ballista drive`'s deck,
// driver/drive_deck.hpp) through drive_point, in memory: no files, so that an optimiser can call
// it thousands of times. The history comes back as a numpy array with the columns of
// `ballista drive`'s history.csv (driver/drive_history.hpp).
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "driver/drive_deck.hpp"
#include "driver/drive_history.hpp"
#include "driver/drive_run.hpp"

namespace py = pybind11;

namespace ballista::python {

namespace {

py::dict drive_deck(const std::string& text, const std::string& file_name, const std::vector<std::string>& overrides,
                    const std::string& base_dir) {
  const DriveDeck deck = parse_drive_deck(text, file_name, overrides, base_dir);
  std::string error;
  DriveResult r;
  {
    py::gil_scoped_release release;
    r = drive_deck_point(deck, error);
  }
  const std::vector<std::string> columns = drive_history_columns(r.state_names);
  py::array_t<double> values({r.records.size(), columns.size()});
  auto v = values.mutable_unchecked<2>();
  for (std::size_t i = 0; i < r.records.size(); ++i) {
    const std::vector<double> row = drive_history_row(r.records[i]);
    for (std::size_t j = 0; j < row.size(); ++j) v(i, j) = row[j];
  }
  py::dict d;
  d["columns"] = columns;
  d["values"] = values;
  d["error"] = error;
  d["steps"] = r.steps;
  d["material"] = deck.material.name;
  d["model"] = deck.material.model;
  d["resolved_yaml"] = deck.resolved_yaml;
  return d;
}

}  // namespace

void bind_drive(py::module_& m) {
  m.def("drive_deck", &drive_deck, py::arg("text"), py::arg("file_name"), py::arg("overrides"), py::arg("base_dir"),
        "Drives one material point by a drive deck given as YAML text; returns the history (columns, "
        "values) and the error that stopped it, if any.");
}

}  // namespace ballista::python
