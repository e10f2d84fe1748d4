// The Python module sharpmesh._core: the library's exceptions and one binding
// file per pipeline stage (io, pointset, features, reconstruct, eval, view,
// stereo, compact).
#include "convert.h"
#include "sharpmesh/errors.h"
#include "sharpmesh/version.h"

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace sharpmesh;
  m.attr("__version__") = SHARPMESH_VERSION;
  // Most specific last: pybind11 tries the translators registered last first.
  // Bad input and bad arguments are also ValueErrors, as Python users expect.
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  static py::exception<InvalidInput> invalid_input(m, "InvalidInput", py::make_tuple(error, py::handle(PyExc_ValueError)));
  static py::exception<InvalidArgument> invalid_argument(m, "InvalidArgument", py::make_tuple(error, py::handle(PyExc_ValueError)));
  static py::exception<NumericalFailure> numerical_failure(m, "NumericalFailure", error.ptr());
  static py::exception<Cancelled> cancelled(m, "Cancelled", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Cancelled& e) {
      PyErr_SetString(cancelled.ptr(), e.what());
    } catch (const InvalidInput& e) {
      PyErr_SetString(invalid_input.ptr(), e.what());
    } catch (const InvalidArgument& e) {
      PyErr_SetString(invalid_argument.ptr(), e.what());
    } catch (const NumericalFailure& e) {
      PyErr_SetString(numerical_failure.ptr(), e.what());
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
  python::bind_io(m);
  python::bind_pointset(m);
  python::bind_features(m);
  python::bind_reconstruct(m);
  python::bind_eval(m);
  python::bind_view(m);
  python::bind_stereo(m);
  python::bind_compact(m);
}
