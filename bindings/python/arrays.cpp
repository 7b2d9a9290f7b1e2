#include "arrays.h"
#include <algorithm>
#include <cmath>

namespace bmfr::python {

namespace {

[[noreturn]] void bad(const char* name, const std::string& what) {
    throw py::value_error(std::string(name) + ": " + what);
}

/// float32 by value, not by the identity of numpy's dtype object (an unpickled array has its own).
bool isFloat32(const py::array& a) {
    return py::isinstance<py::array_t<float>>(a);
}

/// A packed float32 copy (or the array itself when it is one already).
using PackedFloats = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// Any array-like of numbers as PackedFloats; empty when it is none.
PackedFloats numbersOf(const py::handle& object) {
    try {
        return PackedFloats::ensure(object);
    } catch (const py::error_already_set&) {
        return {};
    }
}

[[noreturn]] void notAnArray(const char* name, const py::handle& object) {
    throw py::type_error(std::string(name) + ": expected a numpy array, got " +
                         std::string(py::str(py::type::of(object).attr("__name__"))));
}

std::string shapeText(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

} // namespace

ImageArg imageArg(const py::handle& object, const char* name, int& height, int& width,
                  int minChannels) {
    if (!py::isinstance<py::array>(object)) notAnArray(name, object);
    py::array a = py::reinterpret_borrow<py::array>(object);
    if (!isFloat32(a))
        bad(name, "dtype " + std::string(py::str(a.dtype())) +
                      ", expected float32 (use .astype(numpy.float32))");
    if (a.ndim() != 3 || a.shape(2) < minChannels || a.shape(2) > 4)
        bad(name,
            "shape " + shapeText(a) + ", expected (height, width, C) with C " +
                (minChannels == 3 ? std::string("3 or 4") : std::to_string(minChannels) + " to 4"));
    if (a.shape(0) <= 0 || a.shape(1) <= 0) bad(name, "empty image " + shapeText(a));
    if (a.shape(0) > 65536 || a.shape(1) > 65536) bad(name, "image " + shapeText(a) + " too large");
    if (height < 0) height = int(a.shape(0)), width = int(a.shape(1));
    if (a.shape(0) != height || a.shape(1) != width)
        bad(name, "shape " + shapeText(a) + ", the colour is " + std::to_string(height) + "x" +
                      std::to_string(width));
    const int channels = int(a.shape(2));
    const py::ssize_t f = sizeof(float);
    // Pixels packed within rows (rows may be padded): a view without a copy.
    const bool inPlace = a.strides(2) == f && a.strides(1) == channels * f &&
                         a.strides(0) >= a.shape(1) * channels * f && a.strides(0) % f == 0;
    if (!inPlace) a = PackedFloats::ensure(a);
    ImageView v;
    v.data = static_cast<const float*>(a.data());
    v.width = width;
    v.height = height;
    v.channels = channels;
    v.rowStride = long(a.strides(0) / f);
    return {a, v};
}

ImageArg channelArg(const py::handle& object, const std::string& name, int height, int width) {
    const char* n = name.c_str();
    if (!py::isinstance<py::array>(object)) notAnArray(n, object);
    py::array a = py::reinterpret_borrow<py::array>(object);
    if (!isFloat32(a)) bad(n, "dtype " + std::string(py::str(a.dtype())) + ", expected float32");
    const bool shapeOk = (a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) == 1)) &&
                         a.shape(0) == height && a.shape(1) == width;
    if (!shapeOk)
        bad(n, "shape " + shapeText(a) + ", expected (" + std::to_string(height) + ", " +
                   std::to_string(width) + ") or (" + std::to_string(height) + ", " +
                   std::to_string(width) + ", 1)");
    const py::ssize_t f = sizeof(float);
    if (!(a.strides(1) == f && a.strides(0) >= width * f && a.strides(0) % f == 0))
        a = PackedFloats::ensure(a);
    ImageView v{static_cast<const float*>(a.data()), width, height, 1, long(a.strides(0) / f)};
    return {a, v};
}

Mat4 matrixArg(const py::handle& object, const char* name) {
    const PackedFloats a = numbersOf(object);
    if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
        bad(name, "expected a 4x4 matrix of numbers");
    Mat4 m;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) m.m[r][c] = a.at(r, c);
    return m;
}

MutableImageView outArg(const py::handle& object, int height, int width) {
    if (!py::isinstance<py::array>(object)) notAnArray("out", object);
    py::array a = py::reinterpret_borrow<py::array>(object);
    if (!isFloat32(a))
        bad("out", "dtype " + std::string(py::str(a.dtype())) + ", expected float32");
    if (a.ndim() != 3 || a.shape(0) != height || a.shape(1) != width ||
        (a.shape(2) != 3 && a.shape(2) != 4))
        bad("out", "shape " + shapeText(a) + ", expected (" + std::to_string(height) + ", " +
                       std::to_string(width) + ", 3) or (" + std::to_string(height) + ", " +
                       std::to_string(width) + ", 4)");
    if (!a.writeable()) bad("out", "the array is read-only");
    const py::ssize_t f = sizeof(float), channels = a.shape(2);
    if (!(a.strides(2) == f && a.strides(1) == channels * f &&
          a.strides(0) >= width * channels * f && a.strides(0) % f == 0))
        bad("out", "its pixels must be packed within rows (a C-contiguous array, rows may be "
                   "padded)");
    return {static_cast<float*>(a.mutable_data()), width, height, int(channels),
            long(a.strides(0) / f)};
}

std::pair<float, float> jitterArg(const py::handle& object) {
    const PackedFloats a = numbersOf(object);
    if (!a || a.ndim() != 1 || a.shape(0) != 2)
        bad("jitter", "expected two numbers (x, y), pixels, got " +
                          std::string(py::str(py::repr(object))).substr(0, 60));
    return {a.at(0), a.at(1)};
}

ImageF imageToWrite(const py::handle& object, const char* name) {
    if (!py::isinstance<py::array>(object)) notAnArray(name, object);
    py::array a = py::reinterpret_borrow<py::array>(object);
    if (!isFloat32(a))
        bad(name, "dtype " + std::string(py::str(a.dtype())) +
                      ", expected float32 (use .astype(numpy.float32))");
    const bool shapeOk = a.ndim() == 2 || (a.ndim() == 3 && a.shape(2) >= 1 && a.shape(2) <= 3);
    if (!shapeOk || a.shape(0) <= 0 || a.shape(1) <= 0 || a.shape(0) > 65536 || a.shape(1) > 65536)
        bad(name, "shape " + shapeText(a) +
                      ", expected (height, width) or (height, width, C) "
                      "with C 1 to 3");
    const auto packed = PackedFloats::ensure(a);
    ImageF image(int(a.shape(1)), int(a.shape(0)), a.ndim() == 2 ? 1 : int(a.shape(2)));
    std::copy(packed.data(), packed.data() + image.pixels.size(), image.data());
    return image;
}

py::array_t<float> toArray(const ImageView& v) {
    py::array_t<float> out({py::ssize_t(v.height), py::ssize_t(v.width), py::ssize_t(v.channels)});
    float* dst = out.mutable_data();
    const long row = long(v.width) * v.channels;
    for (int y = 0; y < v.height; ++y)
        std::copy(v.data + y * v.stride(), v.data + y * v.stride() + row, dst + y * row);
    return out;
}

} // namespace bmfr::python
