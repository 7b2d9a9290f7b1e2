#include "filter_binding.h"
#include "arrays.h"
#include "errors.h"
#include "filters/filter_inputs.h"
#include "temporal/frame_buffers.h"
#include <algorithm>
#include <bmfr/bmfr.hpp>
#include <mutex>
#include <pybind11/stl.h>
#include <set>

namespace bmfr::python {

std::string pythonName(const SettingDoc& d) {
    std::string n = d.flag;
    std::replace(n.begin(), n.end(), '-', '_');
    return n;
}

std::vector<std::string> inputBufferNames() {
    std::vector<std::string> names;
    for (const FrameBuffer& b : kFrameBuffers) names.push_back(b.file);
    return names;
}

namespace {

std::string keywordOf(const std::string& filter, const std::string& key) {
    for (const SettingDoc& d : filterSettings(filter))
        if (d.key == key) return pythonName(d);
    return key;
}

/// The settings-table key for a Python keyword: the key itself ("blockSize") or its flag with
/// underscores ("block_size" for --block-size).
std::string settingKey(const std::string& filter, const std::string& name) {
    for (const SettingDoc& d : filterSettings(filter))
        if (d.key == name || pythonName(d) == name) return d.key;
    throw py::type_error("Filter(): " + name + " is not a setting of the " + filter +
                         " filter (bmfr.settings(\"" + filter + "\") lists them)");
}

std::string settingText(const std::string& name, const py::handle& v) {
    if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
    if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) || py::isinstance<py::str>(v))
        return std::string(py::str(v));
    if (py::hasattr(v, "__index__")) // numpy's integers
        return std::string(py::str(py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()))));
    if (py::hasattr(v, "__float__"))
        return std::string(py::str(py::float_(py::reinterpret_borrow<py::object>(v))));
    throw py::type_error(name + ": expected a bool, number or string, got " +
                         std::string(py::str(py::type::of(v).attr("__name__"))));
}

Backend backendNamed(const std::string& name) {
    for (Backend b : {Backend::Cpu, Backend::Reference, Backend::Cuda})
        if (name == backendName(b)) return b;
    throw py::value_error("backend: '" + name + "' is not one of cpu, reference, cuda");
}

/// denoise's positional parameters, in order, and the keywords it takes besides the buffers.
const char* const kPositional[] = {"color",    "albedo",          "normal",
                                   "position", "view_projection", "jitter"};
/// A read_sequence frame's keys that denoise takes and does not use.
const char* const kFrameOnly[] = {"index", "reference"};

/// The filters of one device run one at a time (bmfr::Device), and a filter is not
/// thread-safe: Python threads take this lock, with the GIL released, around every call.
using RunLock = std::shared_ptr<std::mutex>;

class PyDevice {
  public:
    PyDevice(const std::string& backend, int threads, int cudaDevice)
        : device_(backendNamed(backend), threads, cudaDevice) {}
    const Device& device() const { return device_; }
    const RunLock& lock() const { return lock_; }
    void reserve(int width, int height) {
        py::gil_scoped_release unlocked;
        const std::lock_guard<std::mutex> held(*lock_);
        device_.reserve(width, height);
    }
    std::string repr() const {
        return "bmfr.Device(backend='" + std::string(backendName(device_.backend())) +
               "', threads=" + std::to_string(device_.threadCount()) +
               (device_.backend() == Backend::Cuda
                    ? ", cuda_device=" + std::to_string(device_.cudaDevice())
                    : std::string()) +
               ")";
    }

  private:
    Device device_;
    RunLock lock_ = std::make_shared<std::mutex>();
};

class PyFilter {
  public:
    PyFilter(const std::string& name, const std::string& preset, const py::object& backend,
             const py::object& device, const py::kwargs& settings)
        : name_(name), preset_(preset) {
        const std::vector<std::string> names = filterNames();
        if (std::find(names.begin(), names.end(), name) == names.end())
            throw py::value_error("name: unknown filter '" + name + "' (" + joined(names) + ")");
        SettingValues values;
        try {
            values = presetSettings(name, preset);
        } catch (const Error&) {
            throw py::value_error("preset: unknown preset '" + preset + "' (quality, faithful)");
        }
        for (const auto& [k, v] : settings) {
            const std::string keyword = py::str(k);
            const std::string key = settingKey(name, keyword);
            const std::string text = settingText(keyword, v);
            values.erase(std::remove_if(values.begin(), values.end(),
                                        [&](const auto& kv) { return kv.first == key; }),
                         values.end());
            values.emplace_back(key, text);
            given_.emplace_back(keyword, std::string(py::repr(v)));
        }
        try {
            if (!device.is_none()) {
                if (!backend.is_none())
                    throw py::type_error("Filter(): give backend= or device=, not both (the "
                                         "device has its backend)");
                const PyDevice& d = device.cast<const PyDevice&>();
                filter_ = d.device().makeFilter(name, values);
                lock_ = d.lock();
                backend_ = backendName(d.device().backend());
            } else {
                backend_ = backend.is_none() ? "cpu" : std::string(py::str(backend));
                values.emplace_back("backend", backend_);
                filter_ = makeFilter(name, values);
                values.pop_back();
            }
        } catch (const SettingError& e) {
            throwSettingError(e, keywordOf(name, e.key()));
        }
        inputs_ = filterInputs(name, values);
    }

    /// denoise(color, albedo, normal, position, view_projection, jitter=(0, 0), *, reset=False,
    /// extras=None, out=None, <optional buffers>...), parsed here so that a mistake is a short
    /// TypeError or ValueError, never an overload dump of the arrays.
    py::array denoise(const py::args& args, const py::kwargs& kwargs) {
        if (args.size() > std::size(kPositional))
            throw py::type_error(
                "denoise() takes at most " + std::to_string(std::size(kPositional)) +
                " positional arguments (" + std::to_string(args.size()) + " given)");
        std::map<std::string, py::object> given;
        for (size_t k = 0; k < args.size(); ++k) given[kPositional[k]] = args[k];
        for (const auto& [k, v] : kwargs) {
            const std::string name = py::str(k);
            if (given.count(name))
                throw py::type_error("denoise() got multiple values for argument '" + name + "'");
            given[name] = py::reinterpret_borrow<py::object>(v);
        }
        return run(given);
    }

    /// A read_sequence frame, every buffer it holds.
    py::array denoiseFrame(const py::dict& frame, const py::object& out) {
        // Owned references: Python code run while the frame is read cannot free them.
        std::map<std::string, py::object> given;
        for (const auto& [k, v] : frame)
            given[std::string(py::str(k))] = py::reinterpret_borrow<py::object>(v);
        if (!out.is_none()) given["out"] = out;
        return run(given);
    }

    py::dict stats() const {
        FrameStats s;
        {
            py::gil_scoped_release unlocked;
            const std::lock_guard<std::mutex> held(*lock_);
            s = filter_->lastStats();
        }
        py::dict stages;
        for (int k = 0; k < s.times.count; ++k) stages[s.times.name[k]] = s.times.ms[k];
        py::dict d;
        d["stage_ms"] = stages;
        d["total_ms"] = s.times.total;
        d["non_finite_inputs"] = s.nonFiniteInputs;
        d["discarded_pixels"] = s.discardedPixels;
        return d;
    }

    py::list inputs() const {
        py::list names;
        for (const FrameBuffer& b : kFrameBuffers)
            if (b.required) names.append(b.file);
        for (const InputUse& use : inputs_) names.append(use.buffer);
        return names;
    }

    std::string repr() const {
        std::string s = "bmfr.Filter('" + name_ + "'";
        if (preset_ != "quality") s += ", preset='" + preset_ + "'";
        s += ", backend='" + backend_ + "'";
        for (const auto& [k, v] : given_) s += ", " + k + "=" + v;
        return s + ")";
    }

    void reset() {
        py::gil_scoped_release unlocked;
        const std::lock_guard<std::mutex> held(*lock_);
        filter_->reset();
    }
    const std::string& name() const { return name_; }

  private:
    static std::string joined(const std::vector<std::string>& names) {
        std::string s;
        for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
        return s;
    }

    py::array run(const std::map<std::string, py::object>& given) {
        // A handle to an object `given` owns for the whole call; empty when absent or None.
        auto take = [&](const char* name) -> py::handle {
            auto it = given.find(name);
            if (it == given.end() || it->second.is_none()) return py::handle();
            return it->second;
        };
        for (const auto& [name, value] : given) {
            bool known = std::count(std::begin(kPositional), std::end(kPositional), name) ||
                         std::count(std::begin(kFrameOnly), std::end(kFrameOnly), name) ||
                         name == "reset" || name == "extras" || name == "out";
            for (const FrameBuffer& b : kFrameBuffers) known = known || name == b.file;
            if (!known)
                throw py::type_error("denoise() got an unexpected argument '" + name +
                                     "' (the buffers: " + joined(inputBufferNames()) + ")");
        }
        int h = -1, w = -1;
        FrameInput in;
        std::vector<ImageArg> kept; // the arrays the views point into
        kept.reserve(kFrameBufferCount);
        for (const FrameBuffer& b : kFrameBuffers) {
            const py::handle object = take(b.file);
            if (!object) {
                if (b.required)
                    throw py::type_error(std::string("denoise() missing required argument '") +
                                         b.file + "'");
                continue;
            }
            kept.push_back(b.channels.hi == 1 ? channelArg(object, b.file, h, w)
                                              : imageArg(object, b.file, h, w, b.channels.lo));
            in.*b.view = kept.back().view;
        }
        std::vector<ImageArg> extraArgs;
        if (const py::handle extras = take("extras")) {
            if (!py::isinstance<py::sequence>(extras) || py::isinstance<py::array>(extras) ||
                py::isinstance<py::str>(extras))
                throw py::type_error("extras: expected a list of (height, width) arrays");
            const py::sequence list = py::reinterpret_borrow<py::sequence>(extras);
            for (size_t k = 0; k < list.size(); ++k)
                extraArgs.push_back(channelArg(list[k], "extras[" + std::to_string(k) + "]", h, w));
            for (const ImageArg& x : extraArgs) in.extras.push_back(x.view);
        }
        const py::handle matrix = take("view_projection");
        if (!matrix) throw py::type_error("denoise() missing required argument 'view_projection'");
        in.viewProjection = matrixArg(matrix, "view_projection");
        if (const py::handle jitter = take("jitter")) {
            const auto [jx, jy] = jitterArg(jitter);
            in.jitter[0] = jx, in.jitter[1] = jy;
        }
        if (const py::handle reset = take("reset"))
            in.reset = py::bool_(py::reinterpret_borrow<py::object>(reset));
        warnOfMissingInputs(in);
        py::array result;
        MutableImageView target;
        if (const py::handle out = take("out")) {
            target = outArg(out, h, w);
            result = py::reinterpret_borrow<py::array>(out);
        } else {
            py::array_t<float> fresh({py::ssize_t(h), py::ssize_t(w), py::ssize_t(3)});
            target = {fresh.mutable_data(), w, h, 3};
            result = fresh;
        }
        {
            py::gil_scoped_release unlocked; // other Python threads run during the frame
            const std::lock_guard<std::mutex> held(*lock_);
            filter_->denoise(in, target);
        }
        return result;
    }

    /// A Python warning, once per message, for an input the filter is designed around.
    void warnOfMissingInputs(const FrameInput& in) {
        const std::string warning = missingInputWarning(inputs_, in);
        if (warning.empty() || warned_.count(warning)) return;
        if (PyErr_WarnEx(PyExc_UserWarning, (name_ + ": " + warning).c_str(), 1) != 0)
            throw py::error_already_set(); // warnings as errors: raised, and raised again
        warned_.insert(warning);
    }

    std::string name_, preset_, backend_;
    std::vector<std::pair<std::string, std::string>> given_; ///< keyword, repr
    std::vector<InputUse> inputs_;
    std::set<std::string> warned_;
    std::unique_ptr<Filter> filter_;
    RunLock lock_ = std::make_shared<std::mutex>(); ///< the device's, or the filter's own
};

} // namespace

void bindFilter(py::module_& m) {
    py::class_<PyDevice>(m, "Device", R"(Where filters run and the worker threads they share.

Device(backend="cpu", threads=0, cuda_device=0): backend cpu, reference or cuda; threads 0 = all
cores; cuda_device the cuda backend's GPU (as CUDA numbers them). Filters made with
Filter(name, device=d) share its threads. reserve(width, height) sizes the buffers of
filters made afterwards, so that their first frame allocates nothing.)")
        .def(py::init<const std::string&, int, int>(), py::arg("backend") = "cpu",
             py::arg("threads") = 0, py::arg("cuda_device") = 0)
        .def("reserve", &PyDevice::reserve, py::arg("width"), py::arg("height"))
        .def("__repr__", &PyDevice::repr);

    py::class_<PyFilter>(m, "Filter", R"(A temporal reconstruction filter, one per sequence.

Filter(name="bmfr", preset="quality", backend="cpu", device=None, **settings): settings by their
flag name with underscores (block_size=32, taa=False) or their key (blockSize=32), over the
preset's; bmfr.settings(name) lists them. Give backend= or device=, not both.)")
        .def(py::init<const std::string&, const std::string&, const py::object&, const py::object&,
                      const py::kwargs&>(),
             py::arg("name") = "bmfr", py::kw_only(), py::arg("preset") = "quality",
             py::arg("backend") = py::none(), py::arg("device") = py::none())
        .def("denoise", &PyFilter::denoise,
             R"(denoise(color, albedo, normal, position, view_projection, jitter=(0, 0), *,
        reset=False, extras=None, out=None, **buffers) -> (height, width, 3) float32 array

Denoises one frame. Images are float32 (height, width, 3) or (height, width, 4) arrays, viewed
without a copy when their pixels are packed. view_projection is this frame's 4x4 world-to-clip
matrix (row-major, column vectors, NDC y down); jitter the sub-pixel offset of the primary rays,
pixels. The optional buffers come by keyword, by the names bmfr.input_buffers() lists (motion,
previous_position, visibility, ...); extras is a list of (height, width) feature buffers for
BMFR's extraK features. out= a float32 (height, width, 3 or 4) array to write into (a fourth
channel is left as it was), returned. A read_sequence frame's "index" and "reference" are
accepted and not used, so f.denoise(**frame) works.)")
        .def("denoise_frame", &PyFilter::denoiseFrame, py::arg("frame"), py::kw_only(),
             py::arg("out") = py::none(),
             "Denoises a frame dict from read_sequence with every buffer it holds (motion "
             "included): the same as denoise(**frame).")
        .def("reset", &PyFilter::reset, "Drops all history (a camera cut).")
        .def_property_readonly("stats", &PyFilter::stats,
                               "Facts about the last frame: stage_ms, total_ms, "
                               "non_finite_inputs, discarded_pixels.")
        .def_property_readonly("inputs", &PyFilter::inputs,
                               "The buffers this filter reads with its settings: the four "
                               "required ones, then the optional ones (\"extras\" for BMFR's "
                               "extra features). A missing one it is designed around gives a "
                               "warning on the first frame without it.")
        .def_property_readonly("name", &PyFilter::name)
        .def("__repr__", &PyFilter::repr);
}

} // namespace bmfr::python
