// How every filter reads one pixel of its input: NaN/Inf replaced and counted, the noise-free
// emission taken out, the colour demodulated. Per pixel and BMFR_HD, over packed planes.
#pragma once
#include "core/vec.h"
#include <cstdint>

namespace bmfr {

/// A frame's input buffers as packed arrays (3 floats per pixel; extras 1), on host or device,
/// one per row of BMFR_FRAME_BUFFERS (temporal/frame_buffers.h) and the motion's depth offset.
/// temporal/input_staging.h makes them from a FrameInput of any stride and channel count.
struct InputPlanes {
    /// The frame's extras (at most 16), then its visibility when it has one.
    static constexpr int kMaxExtras = 17;
    const float* color = nullptr;
    const float* albedo = nullptr;
    const float* normal = nullptr;
    const float* position = nullptr;
    const float* emission = nullptr;         ///< null when the frame has none
    const float* sampleMask = nullptr;       ///< null at 1 spp
    const float* motion = nullptr;           ///< 2 floats per pixel; null: reproject by camera
    const float* motionDepth = nullptr;      ///< motion's third channel (depth offset), or null
    const float* diffuseIndirect = nullptr;  ///< demodulated diffuse indirect, or null
    const float* previousPosition = nullptr; ///< null: the current position stands in
    const float* previousNormal = nullptr;   ///< null: the current normal stands in
    // Mara et al. 2017's factorisation (FrameInput::matteIndirect ...); each null when absent.
    const float* matteIndirect = nullptr;
    const float* glossyIndirect = nullptr;
    const float* directLight = nullptr;
    const float* specularF0 = nullptr;
    const float* roughness = nullptr;         ///< 1 float per pixel
    const float* glossyHitDistance = nullptr; ///< 1 float per pixel
    const float* visibility = nullptr;        ///< 1 float per pixel; also the last extra
    const float* extras[kMaxExtras] = {};
    int extraCount = 0;
    int width = 0, height = 0;
};

/// How the colour is to be read.
struct InputModes {
    bool colorIsDemodulated = false; ///< the input already is colour / albedo
    bool demodulate = true;          ///< divide by the guarded albedo (unless it already is)
    float albedoEpsilon = 0.001f;
};

BMFR_HD float finiteOrZero(float a, int64_t& replaced) {
    if (std::isfinite(a)) return a;
    ++replaced;
    return 0.0f;
}

BMFR_HD Vec3 finiteOrZero(Vec3 v, int64_t& replaced) {
    if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) return v;
    return {finiteOrZero(v.x, replaced), finiteOrZero(v.y, replaced), finiteOrZero(v.z, replaced)};
}

/// Albedo as used for (de)modulation: finite and at least eps per channel.
BMFR_HD float guardAlbedo(float v, float eps) {
    return std::isfinite(v) && v > eps ? v : eps;
}
BMFR_HD Vec3 guardAlbedo(Vec3 a, float eps) {
    return {guardAlbedo(a.x, eps), guardAlbedo(a.y, eps), guardAlbedo(a.z, eps)};
}

/// One pixel's inputs as every filter reads them.
struct PixelInput {
    Vec3 normal, position, color, albedo;
};

/// Pixel i's colour as readPixel gives it, with its (finite) albedo.
BMFR_HD Vec3 readColor(const InputPlanes& in, long i, const InputModes& modes, Vec3 albedo,
                       int64_t& bad) {
    Vec3 c = finiteOrZero(load3(in.color, i), bad);
    const Vec3 g = guardAlbedo(albedo, modes.albedoEpsilon);
    if (in.emission) {
        Vec3 e = finiteOrZero(load3(in.emission, i), bad);
        if (modes.colorIsDemodulated) e = {e.x / g.x, e.y / g.y, e.z / g.z};
        c = vmax(c - e, Vec3{0, 0, 0});
    }
    if (modes.demodulate && !modes.colorIsDemodulated) c = {c.x / g.x, c.y / g.y, c.z / g.z};
    return c;
}

/// Reads pixel i: NaN/Inf replaced by 0 and counted in `bad` (extras included); the noise-free
/// emission taken out of the colour (demodulated too when the colour is); and, with
/// modes.demodulate, the colour divided by the guarded albedo unless it already is.
BMFR_HD PixelInput readPixel(const InputPlanes& in, long i, const InputModes& modes, int64_t& bad) {
    PixelInput px;
    px.normal = finiteOrZero(load3(in.normal, i), bad);
    px.position = finiteOrZero(load3(in.position, i), bad);
    px.albedo = finiteOrZero(load3(in.albedo, i), bad);
    px.color = readColor(in, i, modes, px.albedo, bad);
    for (int k = 0; k < in.extraCount; ++k)
        if (!std::isfinite(in.extras[k][i])) ++bad;
    return px;
}

} // namespace bmfr
