// WALR's regression features (paper section 5.2): the view-space normal in two octahedral
// coordinates (Cigolle et al. 2014), remapped to [0, 1]. Camera-facing normals fill the inner
// diamond, so the features are continuous over everything the camera sees.
#pragma once
#include "core/view_basis.h"
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

/// The two features of a surface with world normal n at world position p: n flipped towards
/// the camera when it faces away (normal mapping), in view space, octahedral, in [0, 1].
BMFR_HD Vec2 walrNormalFeatures(Vec3 n, Vec3 p, const ViewBasis& view) {
    if (dot(n, view.eye - p) < 0) n = -1.0f * n;
    const Vec2 o = octahedralEncode({dot(n, view.right), dot(n, view.down), dot(n, view.toward)});
    return {0.5f * o.x + 0.5f, 0.5f * o.y + 0.5f};
}

} // namespace bmfr
