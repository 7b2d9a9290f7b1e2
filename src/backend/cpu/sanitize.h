// Replacing non-finite input values, with a count for the caller's warning.
#pragma once
#include "core/vec.h"
#include <cstdint>

namespace bmfr::cpu {

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

} // namespace bmfr::cpu
