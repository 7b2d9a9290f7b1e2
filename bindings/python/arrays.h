// numpy arrays as the library's image views: float32 HxWx3 (or HxWx4), viewed in place when the
// pixels are packed, copied otherwise; errors name the argument.
#pragma once
#include "core/image.h"
#include <bmfr/frame.h>
#include <pybind11/numpy.h>
#include <string>

namespace bmfr::python {

namespace py = pybind11;

/// An image argument, checked: keeps the array (or its contiguous copy) alive with the view.
struct ImageArg {
    py::array array;
    ImageView view;
};

/// Throws TypeError naming `name` for an object that is not an array, ValueError for a wrong
/// dtype, rank, channel count or size.
/// `height`/`width` < 0 take the size from this array.
ImageArg imageArg(const py::handle& object, const char* name, int& height, int& width,
                  int minChannels = 3);

/// A one-channel image argument: float32 (height, width) or (height, width, 1) of the given size.
ImageArg channelArg(const py::handle& object, const std::string& name, int height, int width);

/// A 4x4 matrix from any array-like of numbers (row-major, acting on column vectors).
Mat4 matrixArg(const py::handle& object, const char* name);

/// An `out=` array: float32 (height, width, 3 or 4), pixels packed within rows, writable.
MutableImageView outArg(const py::handle& object, int height, int width);

/// A jitter argument: two numbers, pixels.
std::pair<float, float> jitterArg(const py::handle& object);

/// An image for write_exr: float32 (height, width) or (height, width, 1 to 3), copied.
ImageF imageToWrite(const py::handle& object, const char* name);

/// A new HxWxC float32 array holding a copy of `view`.
py::array_t<float> toArray(const ImageView& view);

} // namespace bmfr::python
