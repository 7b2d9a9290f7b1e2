#include "temporal/input_staging.h"
#include <bmfr/error.h>
#include <string>

namespace bmfr {

const float* InputStaging::packed(const ImageView& v, int channels, std::vector<float>& copy,
                                  int first) {
    if (!v.data) return nullptr;
    if (first == 0 && v.channels == channels && v.stride() == long(v.width) * channels)
        return v.data;
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
    InputPlanes& p = planes_;
    p.width = f.color.width, p.height = f.color.height;
    p.color = packed(f.color, 3, color_);
    p.albedo = packed(f.albedo, 3, albedo_);
    p.normal = packed(f.normal, 3, normal_);
    p.position = packed(f.position, 3, position_);
    p.emission = packed(f.emission, 3, emission_);
    p.sampleMask = packed(f.sampleMask, 1, sampleMask_);
    p.motion = packed(f.motion, 2, motion_);
    p.motionDepth = f.motion.channels >= 3 ? packed(f.motion, 1, motionDepth_, 2) : nullptr;
    p.diffuseIndirect = packed(f.diffuseIndirect, 3, diffuseIndirect_);
    p.previousPosition = packed(f.previousPosition, 3, previousPosition_);
    p.previousNormal = packed(f.previousNormal, 3, previousNormal_);
    p.matteIndirect = packed(f.matteIndirect, 3, matte_);
    p.glossyIndirect = packed(f.glossyIndirect, 3, glossy_);
    p.directLight = packed(f.directLight, 3, direct_);
    p.specularF0 = packed(f.specularF0, 3, f0_);
    p.roughness = packed(f.roughness, 1, roughness_);
    p.glossyHitDistance = packed(f.glossyHitDistance, 1, hitDistance_);
    p.extraCount = int(f.extras.size());
    for (int e = 0; e < p.extraCount; ++e) p.extras[e] = packed(f.extras[size_t(e)], 1, extras_[e]);
    return p;
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
    const long stride = out.stride();
    for (int y = 0; y < in.height; ++y) {
        const float* src = in.data + long(y) * in.width * 3;
        float* dst = out.data + long(y) * stride;
        for (int x = 0; x < in.width; ++x)
            for (int c = 0; c < 3; ++c) dst[x * out.channels + c] = src[3 * x + c];
    }
}

} // namespace bmfr
