// Owning interleaved float/byte images; allocated once, reused every frame.
#pragma once
#include "core/staggered_allocator.h"
#include <bmfr/frame.h>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bmfr {

template <typename T> struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<T, StaggeredAllocator<T>> pixels; ///< each image at its own cache lines

    Image() = default;
    Image(int w, int h, int c) { resize(w, h, c); }
    /// `padding` zeroed elements follow the last pixel, for SIMD loads that read past it.
    void resize(int w, int h, int c, int padding = 0) {
        width = w, height = h, channels = c;
        pixels.assign(size_t(w) * size_t(h) * size_t(c) + size_t(padding), T{});
    }
    long pixelCount() const { return long(width) * height; }
    T* data() { return pixels.data(); }
    const T* data() const { return pixels.data(); }
    T& at(int x, int y, int c = 0) { return pixels[(size_t(y) * width + x) * channels + c]; }
    const T& at(int x, int y, int c = 0) const {
        return pixels[(size_t(y) * width + x) * channels + c];
    }
};

using ImageF = Image<float>;
using ImageU8 = Image<uint8_t>;

/// `out` = the single-channel `in` as floats, resized when its size differs (the debug views
/// of history counts and accept masks; no allocation once sized).
inline void widenToFloat(const ImageU8& in, ImageF& out) {
    if (out.width != in.width || out.height != in.height) out.resize(in.width, in.height, 1);
    for (long i = 0; i < in.pixelCount(); ++i) out.data()[i] = in.data()[i];
}

inline ImageView view(const ImageF& img) {
    return ImageView{img.data(), img.width, img.height, img.channels};
}

} // namespace bmfr
