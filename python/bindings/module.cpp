// ballista._ballista: the C++ side of the Python module. Errors become Python exceptions that
// keep what the C++ error knows (a deck error's file, line, column and key path).
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "core/build_info.hpp"
#include "core/console_log.hpp"
#include "core/error.hpp"

namespace py = pybind11;

namespace ballista::python {

void bind_errors(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<DeckError> deck_error(m, "DeckError", error.ptr());
  static py::exception<PhysicsError> physics_error(m, "PhysicsError", error.ptr());
  error.doc() = "Any error Ballista reports (base of DeckError and PhysicsError).";
  deck_error.doc() = "A bad deck: the message names the file, line, column and key path; so do the "
                     "attributes file, line, column (1-based, 0 = unknown) and key_path.";
  physics_error.doc() = "A run or a driven point that cannot continue (NaN, inverted point, ...).";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const DeckError& e) {
      py::object exc = py::reinterpret_borrow<py::object>(deck_error.ptr())(e.what());
      exc.attr("file") = e.file();
      exc.attr("line") = e.line();
      exc.attr("column") = e.column();
      exc.attr("key_path") = e.key_path();
      PyErr_SetObject(deck_error.ptr(), exc.ptr());
    } catch (const PhysicsError& e) {
      physics_error(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

}  // namespace ballista::python

PYBIND11_MODULE(_ballista, m) {
  m.doc() = "Ballista's C++ core; use the package `ballista`, not this module.";
  // Diagnostics on standard error, as the command line has them (core/console_log.hpp).
  ballista::log_to_stderr();
  m.attr("commit") = ballista::build_commit();
#ifdef BALLISTA_VERSION
  m.attr("version") = BALLISTA_VERSION;
#endif
  ballista::python::bind_errors(m);
  ballista::python::bind_run(m);
  ballista::python::bind_drive(m);
  ballista::python::bind_models(m);
}
