#include "temporal/frame_checks.h"
#include "core/mat4.h"
#include <bmfr/error.h>
#include <cmath>
#include <string>

namespace bmfr {

namespace {

/// Channels a buffer may have: [lo, hi].
struct ChannelRange {
    int lo, hi;
};
constexpr ChannelRange kRgb{3, 4}, kScalar{1, 1}, kMotion{2, 4};

void checkImage(const ImageView& v, const std::string& name, ChannelRange channels, int w, int h) {
    if (!v.data) throw Error("input buffer '" + name + "' is missing");
    if (v.width <= 0 || v.height <= 0)
        throw Error("input buffer '" + name + "' has zero size (" + std::to_string(v.width) + "x" +
                    std::to_string(v.height) + ")");
    if (v.channels < channels.lo || v.channels > channels.hi)
        throw Error("input buffer '" + name + "' has " + std::to_string(v.channels) +
                    " channels, expected " +
                    (channels.lo == channels.hi ? std::to_string(channels.lo)
                     : channels.hi == channels.lo + 1
                         ? std::to_string(channels.lo) + " or " + std::to_string(channels.hi)
                         : std::to_string(channels.lo) + " to " + std::to_string(channels.hi)));
    if (v.width != w || v.height != h)
        throw Error("input buffer '" + name + "' is " + std::to_string(v.width) + "x" +
                    std::to_string(v.height) + ", colour is " + std::to_string(w) + "x" +
                    std::to_string(h));
    if (v.rowStride != 0 && v.rowStride < long(v.width) * v.channels)
        throw Error("input buffer '" + name + "' has a row stride of " +
                    std::to_string(v.rowStride) + " floats, less than a row (" +
                    std::to_string(long(v.width) * v.channels) + ")");
}

} // namespace

void checkFrameInput(const FrameInput& f, int extrasNeeded) {
    const int w = f.color.width, h = f.color.height;
    checkImage(f.color, "color", kRgb, w, h);
    checkImage(f.albedo, "albedo", kRgb, w, h);
    checkImage(f.normal, "normal", kRgb, w, h);
    checkImage(f.position, "position", kRgb, w, h);
    if (f.emission.data) checkImage(f.emission, "emission", kRgb, w, h);
    if (f.motion.data) checkImage(f.motion, "motion", kMotion, w, h);
    if (f.previousPosition.data) checkImage(f.previousPosition, "previousPosition", kRgb, w, h);
    if (f.previousNormal.data) checkImage(f.previousNormal, "previousNormal", kRgb, w, h);
    if (f.diffuseIndirect.data) checkImage(f.diffuseIndirect, "diffuseIndirect", kRgb, w, h);
    if (f.matteIndirect.data) checkImage(f.matteIndirect, "matteIndirect", kRgb, w, h);
    if (f.glossyIndirect.data) checkImage(f.glossyIndirect, "glossyIndirect", kRgb, w, h);
    if (f.directLight.data) checkImage(f.directLight, "directLight", kRgb, w, h);
    if (f.specularF0.data) checkImage(f.specularF0, "specularF0", kRgb, w, h);
    if (f.roughness.data) checkImage(f.roughness, "roughness", kScalar, w, h);
    if (f.glossyHitDistance.data)
        checkImage(f.glossyHitDistance, "glossyHitDistance", kScalar, w, h);
    if (f.extras.size() > 16) throw Error("at most 16 extra buffers");
    for (size_t e = 0; e < f.extras.size(); ++e)
        checkImage(f.extras[e], "extra" + std::to_string(e), kScalar, w, h);
    if (extrasNeeded > int(f.extras.size()))
        throw Error("feature extra" + std::to_string(extrasNeeded - 1) + " needs " +
                    std::to_string(extrasNeeded) + " extra buffers, the frame has " +
                    std::to_string(f.extras.size()));
    if (f.sampleMask.data) checkImage(f.sampleMask, "sampleMask", kScalar, w, h);
    if (!isUsableCameraMatrix(f.viewProjection))
        throw Error("view-projection matrix is not finite or not invertible");
    for (float j : f.jitter)
        if (!std::isfinite(j) || std::fabs(j) > 1.0f)
            throw Error("sub-pixel jitter " + std::to_string(j) + " is outside [-1, 1] pixels");
}

} // namespace bmfr
