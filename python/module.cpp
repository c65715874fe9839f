// `import talus`: the extension module talus._talus (the package's __init__.py re-exports it).
#include "python/bindings.h"

#include "engine/simulation.h"
#include "io/common/input_error.h"
#include "io/common/write_error.h"

namespace py = pybind11;

namespace talus::python {

void registerExceptions(py::module_& m) {
  // InputError keeps its file, line and key as attributes; the message is the same one line the
  // talus program prints.
  static py::exception<InputError> inputError(m, "InputError", PyExc_ValueError);
  static py::exception<NumericalError> numericalError(m, "NumericalError", PyExc_ArithmeticError);
  static py::exception<WriteError> writeError(m, "WriteError", PyExc_OSError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object err = py::handle(inputError.ptr())(e.what());
      err.attr("file") = e.file();
      err.attr("line") = e.line();
      err.attr("key") = e.key();
      PyErr_SetObject(inputError.ptr(), err.ptr());
    } catch (const NumericalError& e) {
      PyErr_SetString(numericalError.ptr(), e.what());
    } catch (const WriteError& e) {
      PyErr_SetString(writeError.ptr(), e.what());
    }
  });
}

} // namespace talus::python

PYBIND11_MODULE(_talus, m) {
  m.doc() = "Talus: three-dimensional MPM of alpine mass movements (docs/python.md)";
  talus::python::registerExceptions(m);
  talus::python::registerScene(m);
  talus::python::registerSimulation(m);
  talus::python::registerAnalysis(m);
}
