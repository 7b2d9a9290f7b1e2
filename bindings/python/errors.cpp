#include "errors.h"
#include <cstring>

namespace bmfr::python {

namespace {

/// A message as a Python string: file bytes in it (a corrupt EXR's attribute names) that are not
/// UTF-8 are escaped, never a UnicodeDecodeError in place of the error.
py::object message(const char* text) {
    return py::reinterpret_steal<py::object>(
        PyUnicode_DecodeUTF8(text, Py_ssize_t(std::strlen(text)), "backslashreplace"));
}

PyObject* gError = nullptr;
PyObject* gSettingError = nullptr;

/// A SettingError raised from C++ with its message already in Python's words.
struct PythonSettingError : SettingError {
    using SettingError::SettingError;
    std::string name;
};

} // namespace

void registerErrors(py::module_& m) {
    // Module-lifetime objects: the references are owned by the module's attributes.
    gError = PyErr_NewExceptionWithDoc(
        "bmfr.Error", "A library error: bad input, an unreadable file, a backend without a device.",
        PyExc_Exception, nullptr);
    gSettingError = PyErr_NewExceptionWithDoc(
        "bmfr.SettingError",
        "A setting that is unknown or out of range; .key, .name (the keyword), .value, .problem.",
        gError, nullptr);
    m.add_object("Error", py::handle(gError));
    m.add_object("SettingError", py::handle(gSettingError));
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const SettingError& e) {
            const auto* named = dynamic_cast<const PythonSettingError*>(&e);
            py::object error = py::reinterpret_steal<py::object>(
                PyObject_CallFunctionObjArgs(gSettingError, message(e.what()).ptr(), nullptr));
            if (!error) return; // the call set its own Python error
            error.attr("key") = e.key();
            error.attr("name") = named ? named->name : e.key();
            error.attr("value") = e.value();
            error.attr("problem") = e.problem();
            PyErr_SetObject(gSettingError, error.ptr());
        } catch (const Error& e) {
            PyErr_SetObject(gError, message(e.what()).ptr());
        }
    });
}

void throwSettingError(const SettingError& e, const std::string& pythonName) {
    PythonSettingError error(pythonName + " " + e.value() + " " + e.problem(), e.key(), e.value(),
                             e.problem());
    error.name = pythonName;
    throw error;
}

} // namespace bmfr::python
