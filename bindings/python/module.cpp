// The Python module `bmfr`: every filter of the library on numpy arrays, with the GIL released
// while a frame is denoised, and the tools' readers for sequences (either layout) and EXR files.
#include "arrays.h"
#include "io/exr.h"
#include "io/sequence.h"
#include <algorithm>
#include <bmfr/bmfr.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

namespace py = pybind11;

namespace bmfr::python {

namespace {

/// The optional input buffers' keywords, for an error message.
std::string bufferList() {
    std::string list;
    for (const FrameBuffer& b : kFrameBuffers)
        if (!b.required) list += (list.empty() ? "" : ", ") + std::string(b.file);
    return list;
}

/// A setting's Python name: its flag with underscores ("block_size").
std::string pythonName(const SettingDoc& d) {
    std::string n = d.flag;
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
}

std::string pythonName(const std::string& filter, const std::string& key) {
    for (const SettingDoc& d : filterSettings(filter))
        if (d.key == key) return pythonName(d);
    return key;
}

/// The settings-table key for a Python keyword: the key itself ("blockSize") or its flag with
/// underscores ("block_size" for --block-size).
std::string settingKey(const std::string& filter, const std::string& name) {
    for (const SettingDoc& d : filterSettings(filter))
        if (d.key == name || pythonName(d) == name) return d.key;
    throw py::value_error(name + ": not a setting of the " + filter +
                          " filter (see bmfr.settings(\"" + filter + "\"))");
}

std::string settingText(const py::handle& v) {
    if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) || py::isinstance<py::str>(v))
        return std::string(py::str(v));
    throw py::value_error("expected a bool, number or string, got " +
                          std::string(py::str(py::type::of(v).attr("__name__"))));
}

class PyFilter {
  public:
    PyFilter(const std::string& name, const std::string& backend, const py::kwargs& settings) {
        const std::vector<std::string> names = filterNames();
        if (std::find(names.begin(), names.end(), name) == names.end())
            throw py::value_error("name: unknown filter '" + name + "'");
        SettingValues values{{"backend", backend}};
        for (const auto& [k, v] : settings) {
            const std::string key = settingKey(name, std::string(py::str(k)));
            try {
                values.push_back({key, settingText(v)});
            } catch (const py::value_error& e) {
                throw py::value_error(std::string(py::str(k)) + ": " + e.what());
            }
        }
        try {
            filter_ = makeFilter(name, values);
        } catch (const SettingError& e) {
            throw py::value_error(pythonName(name, e.key()) + " " + e.value() + " " + e.problem());
        } catch (const Error& e) {
            throw py::value_error(e.what());
        }
    }

    /// The buffers of BMFR_FRAME_BUFFERS by their file names: the four required ones, and any
    /// optional ones in `buffers` (None leaves the view empty).
    py::array_t<float> denoise(const py::handle& color, const py::handle& albedo,
                               const py::handle& normal, const py::handle& position,
                               const py::handle& viewProjection, std::pair<float, float> jitter,
                               bool reset, const py::handle& extras, const py::kwargs& buffers) {
        const py::handle required[] = {color, albedo, normal, position};
        for (const auto& item : buffers) {
            const std::string name = py::str(item.first);
            bool known = false;
            for (const FrameBuffer& b : kFrameBuffers)
                known = known || (!b.required && name == b.file);
            if (!known)
                throw py::value_error(name + ": not an input buffer (" + bufferList() + ")");
        }
        int h = -1, w = -1;
        FrameInput in;
        std::vector<ImageArg> kept; // the arrays the views point into
        kept.reserve(kFrameBufferCount);
        int requiredIndex = 0;
        for (const FrameBuffer& b : kFrameBuffers) {
            const py::handle object = b.required                 ? required[requiredIndex++]
                                      : buffers.contains(b.file) ? buffers[b.file]
                                                                 : py::handle(py::none());
            if (object.is_none()) continue;
            kept.push_back(b.channels.hi == 1 ? channelArg(object, b.file, h, w)
                                              : imageArg(object, b.file, h, w, b.channels.lo));
            in.*b.view = kept.back().view;
        }
        std::vector<ImageArg> extraArgs;
        if (!extras.is_none()) {
            if (!py::isinstance<py::sequence>(extras) || py::isinstance<py::array>(extras))
                throw py::value_error("extras: expected a list of (height, width) arrays");
            const py::sequence list = py::reinterpret_borrow<py::sequence>(extras);
            for (size_t k = 0; k < list.size(); ++k)
                extraArgs.push_back(channelArg(list[k], "extras[" + std::to_string(k) + "]", h, w));
            for (const ImageArg& x : extraArgs) in.extras.push_back(x.view);
        }
        in.viewProjection = matrixArg(viewProjection, "view_projection");
        in.jitter[0] = jitter.first, in.jitter[1] = jitter.second;
        in.reset = reset;
        py::array_t<float> out({py::ssize_t(h), py::ssize_t(w), py::ssize_t(3)});
        const MutableImageView target{out.mutable_data(), w, h, 3};
        try {
            py::gil_scoped_release unlocked; // other Python threads run during the frame
            filter_->denoise(in, target);
        } catch (const Error& err) {
            throw py::value_error(err.what());
        }
        return out;
    }

    py::dict stats() const {
        const FrameStats& s = filter_->lastStats();
        py::dict stages;
        for (int k = 0; k < s.times.count; ++k) stages[s.times.name[k]] = s.times.ms[k];
        py::dict d;
        d["stage_ms"] = stages;
        d["total_ms"] = s.times.total;
        d["non_finite_inputs"] = s.nonFiniteInputs;
        d["discarded_pixels"] = s.discardedPixels;
        return d;
    }

    void reset() { filter_->reset(); }
    std::string name() const { return filter_->name(); }

  private:
    std::unique_ptr<Filter> filter_;
};

py::dict sequenceInfo(const SequenceInfo& i) {
    py::dict d;
    d["layout"] = i.layout;
    d["directory"] = i.directory;
    d["frame_count"] = i.frameCount;
    d["width"] = i.width;
    d["height"] = i.height;
    d["color_is_demodulated"] = i.colorIsDemodulated;
    d["has_reference"] = i.hasReference;
    d["position_limit_squared"] =
        i.positionLimitSquared ? py::object(py::float_(*i.positionLimitSquared)) : py::none();
    d["normal_limit_squared"] =
        i.normalLimitSquared ? py::object(py::float_(*i.normalLimitSquared)) : py::none();
    d["extras"] = i.extraNames;
    return d;
}

py::array_t<float> matrixArray(const Mat4& m) {
    py::array_t<float> a({4, 4});
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) a.mutable_at(r, c) = m.m[r][c];
    return a;
}

/// Frames of a sequence, loaded one at a time as dicts of arrays.
class SequenceIterator {
  public:
    SequenceIterator(const std::string& path, const std::map<std::string, std::string>& layers)
        : reader_(open(path)) {
        reader_->setLayerOverrides(layers);
    }
    py::dict next() {
        if (index_ >= reader_->info().frameCount) throw py::stop_iteration();
        try {
            py::gil_scoped_release unlocked;
            reader_->load(index_, frame_);
        } catch (const Error& e) {
            throw py::value_error(e.what());
        }
        py::dict d;
        d["index"] = index_++;
        frame_.forEachBuffer([&d](const FrameBuffer& b, const ImageF& image) {
            if (b.required || image.width) d[b.file] = toArray(view(image));
        });
        d["view_projection"] = matrixArray(frame_.viewProjection);
        d["jitter"] = py::make_tuple(frame_.jitter[0], frame_.jitter[1]);
        d["reset"] = frame_.reset;
        if (frame_.reference.width) d["reference"] = toArray(view(frame_.reference));
        py::list extras;
        for (const ImageF& e : frame_.extras) extras.append(toArray(view(e)));
        d["extras"] = extras;
        return d;
    }
    const SequenceInfo& info() const { return reader_->info(); }
    int size() const { return reader_->info().frameCount; }

    static std::unique_ptr<SequenceReader> open(const std::string& path) {
        try {
            return SequenceReader::open(path);
        } catch (const Error& e) {
            throw py::value_error(e.what());
        }
    }

  private:
    std::unique_ptr<SequenceReader> reader_;
    FrameData frame_;
    int index_ = 0;
};

} // namespace

} // namespace bmfr::python

PYBIND11_MODULE(bmfr, m) {
    using namespace bmfr;
    using namespace bmfr::python;
    m.doc() =
        "bmfr: real-time reconstruction of 1-spp path-traced frame sequences (BMFR, SVGF, WALR, "
        "Mara 2017)";
    m.attr("__version__") = BMFR_VERSION;
    // Every library error (bad input, unreadable files) is a bmfr.Error, a ValueError.
    py::register_exception<Error>(m, "Error", PyExc_ValueError);

    py::class_<PyFilter>(m, "Filter", R"(A temporal reconstruction filter, one per sequence.

Filter(name="bmfr", backend="cpu", **settings): settings by their flag name with underscores
(block_size=32, taa=False) or their key (blockSize=32); bmfr.settings(name) lists them.)")
        .def(py::init<const std::string&, const std::string&, const py::kwargs&>(),
             py::arg("name") = "bmfr", py::arg("backend") = "cpu")
        .def("denoise", &PyFilter::denoise, py::arg("color"), py::arg("albedo"), py::arg("normal"),
             py::arg("position"), py::arg("view_projection"),
             py::arg("jitter") = std::pair<float, float>(0.0f, 0.0f), py::kw_only(),
             py::arg("reset") = false, py::arg("extras") = py::none(),
             R"(Denoises one frame; returns a new (height, width, 3) float32 array.

The optional buffers come by keyword, by the names bmfr.input_buffers() lists.

Images are float32 (height, width, 3) or (height, width, 4) arrays, viewed without a copy when
their pixels are packed. view_projection is this frame's 4x4 world-to-clip matrix (row-major,
column vectors, NDC y down); jitter the sub-pixel offset of the primary rays, pixels. extras:
a list of float32 (height, width) feature buffers for BMFR's extraK features. motion:
(height, width, 2..4) pixels from each pixel to where its surface was in the previous frame
(x right, y down, both frames' jitter included); previous_position and previous_normal: that
surface's previous world position and normal, for moving objects; a third motion channel is the
depth offset. diffuse_indirect: the demodulated diffuse indirect light, for WALR's
signal="diffuse-indirect". matte_indirect, glossy_indirect, direct_light, specular_f0 and the
single-channel roughness and glossy_hit_distance: Mara et al. 2017's factorisation, for
"mara2017". visibility: (height, width) noise-free sun (key light) visibility times its
cosine, for BMFR's visibility_feature (bmfr::FrameInput).)")
        .def("reset", &PyFilter::reset, "Drops all history (a camera cut).")
        .def_property_readonly("stats", &PyFilter::stats,
                               "Facts about the last frame: stage_ms, total_ms, "
                               "non_finite_inputs, discarded_pixels.")
        .def_property_readonly("name", &PyFilter::name);

    py::class_<SequenceIterator>(m, "Sequence")
        .def("__iter__", [](SequenceIterator& s) -> SequenceIterator& { return s; })
        .def("__next__", &SequenceIterator::next)
        .def("__len__", &SequenceIterator::size)
        .def_property_readonly("info",
                               [](const SequenceIterator& s) { return sequenceInfo(s.info()); });

    m.def(
        "read_sequence",
        [](const std::string& path, const std::map<std::string, std::string>& channels) {
            return SequenceIterator(path, channels);
        },
        py::arg("path"), py::arg("channels") = std::map<std::string, std::string>(),
        "The frames of a sequence folder (this project's sequence.json or the original BMFR "
        "layout), one dict of arrays per frame; .info describes the sequence. channels maps a "
        "buffer to a multilayer EXR layer, as {'albedo': 'ViewLayer.DiffCol'}.");
    m.def(
        "read_exr",
        [](const std::string& path, int channels) {
            try {
                return toArray(view(readExr(path, channels)));
            } catch (const Error& e) {
                throw py::value_error(e.what());
            }
        },
        py::arg("path"), py::arg("channels") = 3,
        "An EXR file as a (height, width, channels) array.");
    m.def("filter_names", &filterNames, "The filters this build holds.");
    m.def(
        "input_buffers",
        [] {
            py::list names;
            for (const FrameBuffer& b : kFrameBuffers) names.append(b.file);
            return names;
        },
        "The image buffers a frame may have, by their keyword in Filter.denoise and their key in "
        "read_sequence's frames: the four required ones first.");
    m.def("backends", &compiledBackends, "The backends this build holds.");
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
        [](const std::string& name, const std::string& preset) {
            py::dict values;
            try {
                for (const auto& [key, value] : presetSettings(name, preset))
                    values[py::str(pythonName(name, key))] = value;
            } catch (const Error& e) {
                throw py::value_error(e.what());
            }
            return values;
        },
        py::arg("name"), py::arg("preset"),
        "The settings a preset (faithful, quality) gives a filter, by Python name: "
        "bmfr.Filter(\"bmfr\", **bmfr.preset(\"bmfr\", \"quality\")).");
}
