// 4x4 matrix helpers on bmfr::Mat4 (row-major, column vectors).
#pragma once
#include "core/vec.h"
#include <bmfr/frame.h>

namespace bmfr {

struct Vec4 {
    float x = 0, y = 0, z = 0, w = 0;
};

/// m * [p, 1]
BMFR_HD Vec4 transformPoint(const Mat4& m, Vec3 p) {
    Vec4 r;
    r.x = m.m[0][0] * p.x + m.m[0][1] * p.y + m.m[0][2] * p.z + m.m[0][3];
    r.y = m.m[1][0] * p.x + m.m[1][1] * p.y + m.m[1][2] * p.z + m.m[1][3];
    r.z = m.m[2][0] * p.x + m.m[2][1] * p.y + m.m[2][2] * p.z + m.m[2][3];
    r.w = m.m[3][0] * p.x + m.m[3][1] * p.y + m.m[3][2] * p.z + m.m[3][3];
    return r;
}

/// The upper 3x3 of m times v: a direction (or, with the inverse transpose, a normal).
BMFR_HD Vec3 transformVector(const Mat4& m, Vec3 v) {
    return {m.m[0][0] * v.x + m.m[0][1] * v.y + m.m[0][2] * v.z,
            m.m[1][0] * v.x + m.m[1][1] * v.y + m.m[1][2] * v.z,
            m.m[2][0] * v.x + m.m[2][1] * v.y + m.m[2][2] * v.z};
}

Mat4 multiply(const Mat4& a, const Mat4& b);
Mat4 transpose(const Mat4& a);
/// Inverse in double precision; returns false when the matrix is singular or not finite.
bool invert(const Mat4& a, Mat4& out);
/// The same, kept in double (positions reconstructed far from the origin need its digits).
bool invert(const Mat4& a, double out[4][4]);
/// True when every entry is finite and the matrix is invertible (a usable camera).
bool isUsableCameraMatrix(const Mat4& a);

/// Right-handed look-at view matrix (camera looks down -z).
Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up);
/// Perspective projection to the library's NDC convention (x right, y down, z in [-1, 1]).
/// fovY in radians, aspect = width / height.
Mat4 perspectiveYDown(float fovY, float aspect, float zNear, float zFar);

} // namespace bmfr
