// WALR's regression features (paper section 5.2): the view-space normal in two octahedral
// coordinates (Cigolle et al. 2014), remapped to [0, 1]. Camera-facing normals fill the inner
// diamond, so the features are continuous over everything the camera sees.
#pragma once
#include "core/mat4.h"
#include <cmath>

namespace bmfr {

/// The camera's axes and centre, recovered from a world-to-clip matrix: `toward` points from the
/// scene to the camera, `right` and `down` follow NDC x and y.
struct ViewBasis {
    Vec3 right{1, 0, 0}, down{0, 1, 0}, toward{0, 0, 1};
    Vec3 eye{};
};

/// The view basis of a perspective (or affine) view-projection matrix: the clip w row is the
/// view axis; the x and y rows, made orthogonal to it, are the image axes; the eye is where
/// clip x, y and w all vanish.
inline ViewBasis viewBasisOf(const Mat4& vp) {
    auto row = [&](int r) { return Vec3{vp.m[r][0], vp.m[r][1], vp.m[r][2]}; };
    ViewBasis b;
    const Vec3 forward = normalize(row(3)), r0 = row(0), r1 = row(1);
    if (!(length(row(3)) > 0)) return b;
    b.toward = -1.0f * forward;
    b.right = normalize(r0 - dot(r0, forward) * forward);
    b.down = normalize(r1 - dot(r1, forward) * forward - dot(r1, b.right) * b.right);
    // Cramer's rule on rows 0, 1 and 3: row . eye = -translation.
    const Vec3 a = r0, c = r1, e = row(3);
    const double det = double(dot(a, cross(c, e)));
    if (std::fabs(det) > 0) {
        const Vec3 rhs{-vp.m[0][3], -vp.m[1][3], -vp.m[3][3]};
        const Vec3 ca{a.x, c.x, e.x}, cb{a.y, c.y, e.y}, cc{a.z, c.z, e.z}; // columns
        b.eye = {float(double(dot(rhs, cross(cb, cc))) / det),
                 float(double(dot(ca, cross(rhs, cc))) / det),
                 float(double(dot(ca, cross(cb, rhs))) / det)};
    }
    return b;
}

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
