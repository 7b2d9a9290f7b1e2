#include "sequence_binding.h"
#include "arrays.h"
#include <pybind11/stl.h>

namespace bmfr::python {

namespace {

py::array_t<float> matrixArray(const Mat4& m) {
    py::array_t<float> a({4, 4});
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) a.mutable_at(r, c) = m.m[r][c];
    return a;
}

} // namespace

Sequence::Sequence(const std::string& path, const std::map<std::string, std::string>& layers)
    : reader_(SequenceReader::open(path)) {
    reader_->setLayerOverrides(layers);
    for (int i = 0; i < reader_->info().frameCount; ++i) indices_.push_back(i);
}

py::dict Sequence::frame(int index) const {
    FrameData f;
    size_t notesBefore = 0;
    {
        py::gil_scoped_release unlocked;
        notesBefore = reader_->notes().size();
        reader_->load(index, f);
    }
    // What the CLI prints as "note:" (Cycles' own denoiser was on, ...), once per sequence.
    const std::vector<std::string> notes = reader_->notes();
    for (size_t k = notesBefore; k < notes.size(); ++k)
        if (PyErr_WarnEx(PyExc_UserWarning, notes[k].c_str(), 1) != 0)
            throw py::error_already_set();
    py::dict d;
    d["index"] = index;
    f.forEachBuffer([&d](const FrameBuffer& b, const ImageF& image) {
        if (b.required || image.width) d[b.file] = toArray(view(image));
    });
    d["view_projection"] = matrixArray(f.viewProjection);
    d["jitter"] = py::make_tuple(f.jitter[0], f.jitter[1]);
    d["reset"] = f.reset;
    if (f.reference.width) d["reference"] = toArray(view(f.reference));
    py::list extras;
    for (const ImageF& e : f.extras) extras.append(toArray(view(e)));
    d["extras"] = extras;
    return d;
}

py::object Sequence::item(const py::object& key) const {
    const auto n = py::ssize_t(indices_.size());
    if (py::isinstance<py::slice>(key)) {
        py::ssize_t start = 0, stop = 0, step = 0, length = 0;
        if (!py::reinterpret_borrow<py::slice>(key).compute(n, &start, &stop, &step, &length))
            throw py::error_already_set();
        std::vector<int> picked;
        for (py::ssize_t k = 0; k < length; ++k)
            picked.push_back(indices_[size_t(start + k * step)]);
        return py::cast(Sequence(reader_, picked));
    }
    if (!py::hasattr(key, "__index__"))
        throw py::type_error("Sequence indices must be integers or slices, not " +
                             std::string(py::str(py::type::of(key).attr("__name__"))));
    const py::int_ index = py::reinterpret_steal<py::int_>(PyNumber_Index(key.ptr()));
    if (index.ptr() == nullptr) throw py::error_already_set();
    py::ssize_t k = PyNumber_AsSsize_t(index.ptr(), nullptr); // clamped: then out of range
    if (k < 0) k += n;
    if (k < 0 || k >= n)
        throw py::index_error("frame " + std::string(py::str(key)) + " is outside a sequence of " +
                              std::to_string(n) + " frames");
    return frame(indices_[size_t(k)]);
}

py::dict Sequence::info() const {
    const SequenceInfo& i = reader_->info();
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

py::dict Sequence::settings() const {
    const SequenceInfo& i = reader_->info();
    py::dict d;
    if (i.positionLimitSquared) d["position_limit"] = *i.positionLimitSquared;
    if (i.normalLimitSquared) d["normal_limit"] = *i.normalLimitSquared;
    if (i.colorIsDemodulated) d["color_is_demodulated"] = true;
    return d;
}

std::string Sequence::repr() const {
    const SequenceInfo& i = reader_->info();
    return "<bmfr.Sequence " + i.directory + ": " + std::to_string(indices_.size()) + " of " +
           std::to_string(i.frameCount) + " frames, " + std::to_string(i.width) + "x" +
           std::to_string(i.height) + ", " + i.layout + " layout>";
}

py::dict SequenceIterator::next() {
    if (position_ >= sequence_.size()) throw py::stop_iteration();
    return sequence_.frame(sequence_.indexAt(position_++));
}

void bindSequence(py::module_& m) {
    py::class_<SequenceIterator>(m, "SequenceIterator")
        .def("__iter__", [](SequenceIterator& s) -> SequenceIterator& { return s; })
        .def("__next__", &SequenceIterator::next);
    py::class_<Sequence>(m, "Sequence", R"(The frames of a sequence folder, loaded one at a time.

Iterate it, index it (seq[0], seq[-1]) or slice it (seq[2:5] is a Sequence); each frame is a dict
of arrays: the buffers by their bmfr.input_buffers() names, "reference" when the sequence has
one, "extras", "view_projection", "jitter", "reset" and "index". Filter.denoise_frame takes it.)")
        .def("__iter__", [](const Sequence& s) { return SequenceIterator(s); })
        .def("__len__", &Sequence::size)
        .def("__getitem__", &Sequence::item)
        .def("__repr__", &Sequence::repr)
        .def_property_readonly("info", &Sequence::info,
                               "layout, directory, frame_count, width, height, "
                               "color_is_demodulated, has_reference, position_limit_squared, "
                               "normal_limit_squared, extras")
        .def_property_readonly(
            "notes", [](const Sequence& s) { return s.notes(); },
            "What bmfr denoise prints as notes about how the frames read so far were read (each "
            "is also a UserWarning when first seen)")
        .def_property_readonly("settings", &Sequence::settings,
                               "What bmfr denoise takes from the sequence, as Filter keywords "
                               "(its discard limits, whether its colour is demodulated): "
                               "bmfr.Filter(name, **seq.settings).");
    m.def(
        "read_sequence",
        [](const std::string& path, const std::map<std::string, std::string>& channels) {
            return Sequence(path, channels);
        },
        py::arg("path"), py::arg("channels") = std::map<std::string, std::string>(),
        "The frames of a sequence folder (this project's sequence.json or the original BMFR "
        "layout) as a bmfr.Sequence; channels maps a buffer to a multilayer EXR layer, as "
        "{'albedo': 'ViewLayer.DiffCol'}.");
}

} // namespace bmfr::python
