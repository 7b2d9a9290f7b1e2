// Unit vectors as two octahedral coordinates in [-1, 1] (Cigolle et al. 2014): WALR's normal
// features, and the packed normals engines hand the C API.
#pragma once
#include "core/vec.h"
#include <cmath>

namespace bmfr {

/// Octahedral coordinates of unit vector v, in [-1, 1]^2; v.z >= 0 maps to the inner diamond.
BMFR_HD Vec2 octahedralEncode(Vec3 v) {
    const float s = std::fabs(v.x) + std::fabs(v.y) + std::fabs(v.z);
    if (!(s > 0)) return {0, 0};
    float u = v.x / s, w = v.y / s;
    if (v.z < 0) {
        const float fu = (1.0f - std::fabs(w)) * (u >= 0 ? 1.0f : -1.0f);
        const float fw = (1.0f - std::fabs(u)) * (w >= 0 ? 1.0f : -1.0f);
        u = fu, w = fw;
    }
    return {u, w};
}

/// The unit vector whose octahedral coordinates are o (the inverse of octahedralEncode).
BMFR_HD Vec3 octahedralDecode(Vec2 o) {
    Vec3 n{o.x, o.y, 1.0f - std::fabs(o.x) - std::fabs(o.y)};
    const float t = n.z < 0 ? -n.z : 0.0f;
    n.x -= (n.x >= 0 ? 1.0f : -1.0f) * t;
    n.y -= (n.y >= 0 ? 1.0f : -1.0f) * t;
    return normalize(n);
}

} // namespace bmfr
