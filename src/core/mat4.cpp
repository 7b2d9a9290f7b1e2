#include "core/mat4.h"
#include <cmath>

namespace bmfr {

Mat4 multiply(const Mat4& a, const Mat4& b) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += double(a.m[i][k]) * b.m[k][j];
            r.m[i][j] = float(s);
        }
    return r;
}

Mat4 transpose(const Mat4& a) {
    Mat4 r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) r.m[i][j] = a.m[j][i];
    return r;
}

bool invert(const Mat4& a, double out[4][4]) {
    double m[4][8];
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            if (!std::isfinite(a.m[i][j])) return false;
            m[i][j] = a.m[i][j];
            m[i][j + 4] = i == j ? 1.0 : 0.0;
        }
    double scale = 0;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) scale = std::fmax(scale, std::fabs(m[i][j]));
    if (scale == 0) return false;
    for (int c = 0; c < 4; ++c) {
        int p = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::fabs(m[r][c]) > std::fabs(m[p][c])) p = r;
        if (std::fabs(m[p][c]) < 1e-12 * scale) return false;
        for (int j = 0; j < 8; ++j) std::swap(m[c][j], m[p][j]);
        double inv = 1.0 / m[c][c];
        for (int j = 0; j < 8; ++j) m[c][j] *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            double f = m[r][c];
            for (int j = 0; j < 8; ++j) m[r][j] -= f * m[c][j];
        }
    }
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out[i][j] = m[i][j + 4];
    return true;
}

bool invert(const Mat4& a, Mat4& out) {
    double inverse[4][4];
    if (!invert(a, inverse)) return false;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) out.m[i][j] = float(inverse[i][j]);
    return true;
}

bool isUsableCameraMatrix(const Mat4& a) {
    Mat4 inv;
    return invert(a, inv);
}

Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up) {
    Vec3 f = normalize(target - eye);
    Vec3 s = normalize(cross(f, up));
    Vec3 u = cross(s, f);
    Mat4 v;
    v.m[0][0] = s.x, v.m[0][1] = s.y, v.m[0][2] = s.z, v.m[0][3] = -dot(s, eye);
    v.m[1][0] = u.x, v.m[1][1] = u.y, v.m[1][2] = u.z, v.m[1][3] = -dot(u, eye);
    v.m[2][0] = -f.x, v.m[2][1] = -f.y, v.m[2][2] = -f.z, v.m[2][3] = dot(f, eye);
    return v;
}

Mat4 perspectiveYDown(float fovY, float aspect, float zNear, float zFar) {
    float t = 1.0f / std::tan(0.5f * fovY);
    Mat4 p;
    p.m[0][0] = t / aspect;
    p.m[1][1] = -t; // flip: rows grow downwards
    p.m[2][2] = (zFar + zNear) / (zNear - zFar);
    p.m[2][3] = 2.0f * zFar * zNear / (zNear - zFar);
    p.m[3][2] = -1.0f;
    p.m[3][3] = 0.0f;
    return p;
}

} // namespace bmfr
