// bmfr.Device and bmfr.Filter: every filter of the library on numpy arrays, with the GIL
// released while a frame is denoised.
#pragma once
#include <bmfr/filter.h>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace bmfr::python {

namespace py = pybind11;

/// A setting's Python name: its flag with underscores ("block_size").
std::string pythonName(const SettingDoc& d);

/// The image buffers a frame may have (bmfr.input_buffers()): the four required ones first.
std::vector<std::string> inputBufferNames();

/// The module's Device and Filter.
void bindFilter(py::module_& m);

} // namespace bmfr::python
