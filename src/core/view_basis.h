// The camera's axes and centre, recovered from a world-to-clip matrix (WALR's view-space
// features, Mara's view direction and virtual positions).
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

} // namespace bmfr
