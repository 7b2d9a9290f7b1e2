// The Python module `bmfr`: every filter of the library on numpy arrays, and the tools' readers
// and writers for sequences (either layout) and EXR files. The signatures editors complete are
// in bmfr.pyi beside the module.
#include "arrays.h"
#include "errors.h"
#include "filter_binding.h"
#include "io/exr.h"
#include "metrics/flip.h"
#include "sequence_binding.h"
#include <bmfr/bmfr.hpp>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

PYBIND11_MODULE(bmfr, m) {
    using namespace bmfr;
    using namespace bmfr::python;
    // Every array the module hands out is numpy's: without numpy, say so at the import, not
    // at the first frame.
    try {
        py::module_::import("numpy");
    } catch (const py::error_already_set&) {
        throw py::import_error("bmfr needs numpy, which this Python (" +
                               std::string(py::str(py::module_::import("sys").attr("executable"))) +
                               ") does not have: pip install numpy");
    }
    m.doc() =
        "bmfr: real-time reconstruction of 1-spp path-traced frame sequences (BMFR, SVGF, WALR, "
        "Mara 2017)";
    m.attr("__version__") = BMFR_VERSION;
    registerErrors(m);
    bindFilter(m);
    bindSequence(m);

    m.def(
        "read_exr",
        [](const std::string& path, int channels, const std::string& layer) {
            if (channels < 1 || channels > 3)
                throw py::value_error("channels: " + std::to_string(channels) +
                                      ", expected 1 to 3");
            ImageF image;
            {
                py::gil_scoped_release unlocked;
                image = readExr(path, channels, layer.empty() ? imageLayer(path) : layer);
            }
            return toArray(view(image));
        },
        py::arg("path"), py::arg("channels") = 3, py::arg("layer") = "",
        "An EXR file as a float32 (height, width, channels) array. layer names a layer of a "
        "multilayer file, as \"ViewLayer.Noisy Image\" (bmfr.exr_channels lists them); by "
        "default a multilayer file gives its Combined pass.");
    m.def(
        "write_exr",
        [](const std::string& path, const py::handle& image) {
            const ImageF copy = imageToWrite(image, "image");
            py::gil_scoped_release unlocked;
            writeExr(path, copy);
        },
        py::arg("path"), py::arg("image"),
        "Writes a float32 (height, width) or (height, width, 1 to 3) array as an EXR (Y, R,G or "
        "R,G,B; ZIP), atomically: a temporary file renamed over `path`.");
    m.def("exr_channels", &exrChannelNames, py::arg("path"),
          "Every channel of an EXR by its full name (\"ViewLayer.Combined.R\", ...).");
    m.def("filter_names", &filterNames, "The filters this build holds.");
    m.def("input_buffers", &inputBufferNames,
          "The image buffers a frame may have, by their keyword in Filter.denoise and their key in "
          "read_sequence's frames: the four required ones first.");
    m.def("backends", &compiledBackends, "The backends this build holds.");
    m.def(
        "flip",
        [](const py::handle& reference, const py::handle& test, double ppd) {
            const ImageF ref = imageToWrite(reference, "reference");
            const ImageF tst = imageToWrite(test, "test");
            if (ref.channels != 3 || tst.channels != 3)
                throw py::value_error("flip: reference and test must be (height, width, 3)");
            if (ref.width != tst.width || ref.height != tst.height)
                throw py::value_error("flip: reference is " + std::to_string(ref.width) + "x" +
                                      std::to_string(ref.height) + ", test " +
                                      std::to_string(tst.width) + "x" + std::to_string(tst.height));
            for (const ImageF* image : {&ref, &tst})
                for (const float v : image->pixels)
                    if (!(v >= 0.0f && v <= 1.0f))
                        throw py::value_error("flip: values must be sRGB-encoded in [0, 1] (LDR "
                                              "FLIP; tone-map linear images first)");
            if (!(ppd > 0.0 && ppd < 1e4)) throw py::value_error("flip: ppd must be in (0, 1e4)");
            ImageF map;
            {
                py::gil_scoped_release unlocked;
                map = flipMap(ref, tst, ppd);
            }
            return py::make_tuple(flipMean(map), toArray(view(map)));
        },
        py::arg("reference"), py::arg("test"), py::arg("ppd") = kFlipDefaultPpd,
        "LDR FLIP (Andersson et al. 2020) of `test` against `reference`, float32 (height, width, "
        "3) sRGB-encoded in [0, 1], at `ppd` pixels per degree (NVIDIA's default 67.02): (mean, "
        "the (height, width, 1) per-pixel map), the metric bmfr eval reports.");
    m.def(
        "settings",
        [](const std::string& name) {
            py::list rows;
            for (const SettingDoc& d : filterSettings(name)) {
                rows.append(py::dict(py::arg("name") = pythonName(d), py::arg("key") = d.key,
                                     py::arg("unit") = d.unit, py::arg("range") = d.range,
                                     py::arg("default") = d.defaultValue,
                                     py::arg("help") = d.help));
            }
            return rows;
        },
        py::arg("name") = "bmfr", "A filter's settings: name, key, unit, range, default, help.");
    m.def(
        "preset",
        [](const std::string& name, const std::string& presetName) {
            SettingValues preset;
            try {
                preset = presetSettings(name, presetName);
            } catch (const Error& e) {
                throw py::value_error(e.what()); // a name the caller gave: an argument mistake
            }
            py::dict values;
            for (const SettingDoc& d : filterSettings(name))
                for (const auto& [key, value] : preset)
                    if (key == d.key) values[py::str(pythonName(d))] = value;
            return values;
        },
        py::arg("name"), py::arg("preset"),
        "The settings a preset gives a filter, by Python name (quality: none, it is the "
        "default; faithful: the papers' values); "
        "bmfr.Filter(name, preset=...) applies them.");
}
