#include "temporal/input_staging.h"
#include <bmfr/error.h>
#include <string>

namespace bmfr {

const float* InputStaging::packed(const ImageView& v, int channels, std::vector<float>& copy,
                                  int first) {
    if (isPacked(v, channels, first)) return v.data;
    const size_t n = size_t(v.width) * size_t(v.height) * size_t(channels);
    if (copy.size() != n) copy.resize(n);
    const long stride = v.stride();
    for (int y = 0; y < v.height; ++y) {
        const float* row = v.data + long(y) * stride;
        float* dst = copy.data() + size_t(y) * size_t(v.width) * size_t(channels);
        for (int x = 0; x < v.width; ++x)
            for (int c = 0; c < channels; ++c)
                dst[x * channels + c] = row[x * v.channels + first + c];
    }
    return copy.data();
}

const InputPlanes& InputStaging::stage(const FrameInput& f) {
    planes_ = stagePlanes(f, [this](const ImageView& v, int channels, int slot, int first) {
        return packed(v, channels, copies_[slot], first);
    });
    return planes_;
}

void checkOutput(const MutableImageView& out, int width, int height) {
    if (!out.data) throw Error("output buffer is missing");
    if (out.width != width || out.height != height)
        throw Error("output buffer is " + std::to_string(out.width) + "x" +
                    std::to_string(out.height) + ", the frame is " + std::to_string(width) + "x" +
                    std::to_string(height));
    if (out.channels != 3 && out.channels != 4)
        throw Error("output buffer has " + std::to_string(out.channels) +
                    " channels, expected 3 or 4");
    if (out.rowStride != 0 && out.rowStride < long(out.width) * out.channels)
        throw Error("output buffer's row stride is less than a row");
}

void writeOutput(const ImageView& in, const MutableImageView& out) {
    checkOutput(out, in.width, in.height);
    if (out.memory == Memory::Cuda)
        throw Error("output buffer is in CUDA device memory, the frame's buffers in host memory");
    const long stride = out.stride();
    for (int y = 0; y < in.height; ++y) {
        const float* src = in.data + long(y) * in.width * 3;
        float* dst = out.data + long(y) * stride;
        for (int x = 0; x < in.width; ++x)
            for (int c = 0; c < 3; ++c) dst[x * out.channels + c] = src[3 * x + c];
    }
}

} // namespace bmfr
