#include "temporal/frame_checks.h"
#include "core/mat4.h"
#include "temporal/frame_buffers.h"
#include <bmfr/error.h>
#include <cmath>
#include <string>
#include <string_view>

namespace bmfr {

namespace {

const char* memoryName(Memory m) {
    return m == Memory::Cuda ? "CUDA device memory" : "host memory";
}

void checkImage(const ImageView& v, std::string_view view, ChannelRange channels, int w, int h,
                Memory memory) {
    // Named as a string only when something is wrong: a frame that passes allocates nothing.
    const auto name = [view] { return std::string(view); };
    if (!v.data) throw Error("input buffer '" + name() + "' is missing");
    if (v.memory != memory)
        throw Error("input buffer '" + name() + "' is in " + memoryName(v.memory) + ", colour in " +
                    memoryName(memory) + ": a frame's buffers must all be in one");
    if (v.width <= 0 || v.height <= 0)
        throw Error("input buffer '" + name() + "' has zero size (" + std::to_string(v.width) +
                    "x" + std::to_string(v.height) + ")");
    if (v.channels < channels.lo || v.channels > channels.hi)
        throw Error("input buffer '" + name() + "' has " + std::to_string(v.channels) +
                    " channels, expected " +
                    (channels.lo == channels.hi ? std::to_string(channels.lo)
                     : channels.hi == channels.lo + 1
                         ? std::to_string(channels.lo) + " or " + std::to_string(channels.hi)
                         : std::to_string(channels.lo) + " to " + std::to_string(channels.hi)));
    if (v.width != w || v.height != h)
        throw Error("input buffer '" + name() + "' is " + std::to_string(v.width) + "x" +
                    std::to_string(v.height) + ", colour is " + std::to_string(w) + "x" +
                    std::to_string(h));
    if (v.rowStride != 0 && v.rowStride < long(v.width) * v.channels)
        throw Error("input buffer '" + name() + "' has a row stride of " +
                    std::to_string(v.rowStride) + " floats, less than a row (" +
                    std::to_string(long(v.width) * v.channels) + ")");
}

} // namespace

bool inDeviceMemory(const FrameInput& frame) {
    return frame.color.memory == Memory::Cuda;
}

void checkFrameInput(const FrameInput& f, int extrasNeeded, const char* backend,
                     bool readsDeviceMemory) {
    const int w = f.color.width, h = f.color.height;
    const Memory m = f.color.memory;
    if (m == Memory::Cuda && !readsDeviceMemory)
        throw Error(std::string("the frame's buffers are in CUDA device memory, which the ") +
                    backend + " backend cannot read: use backend cuda");
    const auto check = [m](const ImageView& v, std::string_view name, ChannelRange c, int width,
                           int height) { checkImage(v, name, c, width, height, m); };
    for (const FrameBuffer& b : kFrameBuffers)
        if (b.required || (f.*b.view).data) check(f.*b.view, b.member, b.channels, w, h);
    if (f.extras.size() > 16) throw Error("at most 16 extra buffers");
    for (size_t e = 0; e < f.extras.size(); ++e)
        check(f.extras[e], "extra" + std::to_string(e), kScalar, w, h);
    if (extrasNeeded > int(f.extras.size()))
        throw Error("feature extra" + std::to_string(extrasNeeded - 1) + " needs " +
                    std::to_string(extrasNeeded) + " extra buffers, the frame has " +
                    std::to_string(f.extras.size()));
    if (!isUsableCameraMatrix(f.viewProjection))
        throw Error("view-projection matrix is not finite or not invertible");
    for (float j : f.jitter)
        if (!std::isfinite(j) || std::fabs(j) > 1.0f)
            throw Error("sub-pixel jitter " + std::to_string(j) + " is outside [-1, 1] pixels");
}

} // namespace bmfr
