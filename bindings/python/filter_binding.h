// bmfr.Device and bmfr.Filter: every filter of the library on numpy arrays, with the GIL
// released while a frame is denoised.
#pragma once
#include <pybind11/pybind11.h>

namespace bmfr::python {

namespace py = pybind11;

/// The module's Device and Filter.
void bindFilter(py::module_& m);

} // namespace bmfr::python
