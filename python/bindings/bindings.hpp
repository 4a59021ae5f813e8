#pragma once
// The extension module ballista._ballista, one file per part (python/bindings/): the Python
// package (python/ballista/) wraps these functions into its public API (docs/python.md).
#include <pybind11/pybind11.h>

namespace ballista::python {

/// ballista.Error, DeckError (file, line, column, key_path), PhysicsError and their translation.
void bind_errors(pybind11::module_& m);
/// run_deck: a run deck's text through run_simulation, with a progress callback.
void bind_run(pybind11::module_& m);
/// drive_deck: a drive deck's text through drive_point, the history as a numpy array.
void bind_drive(pybind11::module_& m);
/// model_list, model_evaluate: the analytic penetration models (src/penetration/model_catalog).
void bind_models(pybind11::module_& m);

}  // namespace ballista::python
