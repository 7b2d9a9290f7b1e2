// The module's exceptions: bmfr.Error for every library error (bad input, unreadable files, a
// backend without a device), bmfr.SettingError (a bmfr.Error) with the setting's key, value and
// problem. Argument mistakes are TypeError or ValueError, with short messages.
#pragma once
#include <bmfr/error.h>
#include <pybind11/pybind11.h>

namespace bmfr::python {

namespace py = pybind11;

/// Adds Error and SettingError to `m` and translates the library's exceptions into them.
void registerErrors(py::module_& m);

/// Raises bmfr.SettingError for `e`, its message naming the setting by its Python keyword.
[[noreturn]] void throwSettingError(const SettingError& e, const std::string& pythonName);

} // namespace bmfr::python
