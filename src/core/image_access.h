// Accessors that per-pixel kernels take instead of containers: a pointer, the size and the row
// stride, so the same BMFR_HD code runs over host or device memory, packed or strided.
#pragma once
#include "core/vec.h"

namespace bmfr {

/// Pixel (x, y), channel c of an image of T is data[y * rowStride + x * channels + c].
template <typename T> struct Pixels {
    T* data = nullptr;
    int width = 0, height = 0, channels = 1;
    long rowStride = 0; ///< elements between rows

    BMFR_HD T* at(int x, int y) const { return data + long(y) * rowStride + long(x) * channels; }
    BMFR_HD Vec3 rgb(int x, int y) const {
        const T* p = at(x, y);
        return {p[0], p[1], p[2]};
    }
    BMFR_HD void setRgb(int x, int y, Vec3 v) const {
        T* p = at(x, y);
        p[0] = v.x, p[1] = v.y, p[2] = v.z;
    }
    BMFR_HD bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
};

/// A packed image (rows `width * channels` apart).
template <typename T> BMFR_HD Pixels<T> packedPixels(T* data, int width, int height, int channels) {
    return Pixels<T>{data, width, height, channels, long(width) * channels};
}

} // namespace bmfr
