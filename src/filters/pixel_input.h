// Replacing non-finite input values, with a count for the caller's warning.
#pragma once
#include "core/vec.h"
#include <bmfr/frame.h>
#include <cstdint>

namespace bmfr {

inline Vec3 finiteOrZero(Vec3 v, int64_t& replaced) {
    if (std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z)) return v;
    auto fix = [&](float a) {
        if (std::isfinite(a)) return a;
        ++replaced;
        return 0.0f;
    };
    return {fix(v.x), fix(v.y), fix(v.z)};
}

/// Albedo as used for (de)modulation: finite and at least eps per channel.
inline Vec3 guardAlbedo(Vec3 a, float eps) {
    auto g = [&](float v) { return std::isfinite(v) && v > eps ? v : eps; };
    return {g(a.x), g(a.y), g(a.z)};
}

/// One pixel's inputs as every filter reads them.
struct PixelInput {
    Vec3 normal, position, color, albedo;
};

/// Reads pixel i: NaN/Inf replaced by 0 and counted in `bad` (extras included); the noise-free
/// emission taken out of the colour (demodulated too when the colour is); and, with
/// `demodulate`, the colour divided by the guarded albedo unless it already is.
inline PixelInput readPixel(const FrameInput& in, long i, bool colorIsDemodulated, bool demodulate,
                            float albedoEpsilon, int64_t& bad) {
    PixelInput px;
    px.normal = finiteOrZero(load3(in.normal.data, i), bad);
    px.position = finiteOrZero(load3(in.position.data, i), bad);
    px.albedo = finiteOrZero(load3(in.albedo.data, i), bad);
    Vec3 c = finiteOrZero(load3(in.color.data, i), bad);
    const Vec3 g = guardAlbedo(px.albedo, albedoEpsilon);
    if (in.emission.data) {
        Vec3 e = finiteOrZero(load3(in.emission.data, i), bad);
        if (colorIsDemodulated) e = {e.x / g.x, e.y / g.y, e.z / g.z};
        c = vmax(c - e, Vec3{0, 0, 0});
    }
    for (const ImageView& e : in.extras)
        if (!std::isfinite(e.data[i])) ++bad;
    if (demodulate && !colorIsDemodulated) c = {c.x / g.x, c.y / g.y, c.z / g.z};
    px.color = c;
    return px;
}

} // namespace bmfr
