// Small vector math shared by every filter and backend.
#pragma once
#include "core/host_device.h"
#include <cmath>

namespace bmfr {

struct Vec2 {
    float x = 0, y = 0;
};

struct Vec3 {
    float x = 0, y = 0, z = 0;
    BMFR_HD float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

BMFR_HD Vec3 operator+(Vec3 a, Vec3 b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
BMFR_HD Vec3 operator-(Vec3 a, Vec3 b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
BMFR_HD Vec3 operator*(Vec3 a, Vec3 b) {
    return {a.x * b.x, a.y * b.y, a.z * b.z};
}
BMFR_HD Vec3 operator*(float s, Vec3 a) {
    return {s * a.x, s * a.y, s * a.z};
}
BMFR_HD Vec3 operator*(Vec3 a, float s) {
    return {s * a.x, s * a.y, s * a.z};
}
BMFR_HD Vec3 operator/(Vec3 a, float s) {
    return {a.x / s, a.y / s, a.z / s};
}
BMFR_HD Vec3& operator+=(Vec3& a, Vec3 b) {
    return a = a + b;
}
BMFR_HD float dot(Vec3 a, Vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
BMFR_HD Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
BMFR_HD float length(Vec3 a) {
    return std::sqrt(dot(a, a));
}
BMFR_HD Vec3 normalize(Vec3 a) {
    return a / length(a);
}
// Plain comparisons, not std::fmin: inputs are sanitised, and these compile to min/max
// instructions instead of library calls.
BMFR_HD float fminFast(float a, float b) {
    return b < a ? b : a;
}
BMFR_HD float fmaxFast(float a, float b) {
    return a < b ? b : a;
}
BMFR_HD Vec3 vmin(Vec3 a, Vec3 b) {
    return {fminFast(a.x, b.x), fminFast(a.y, b.y), fminFast(a.z, b.z)};
}
BMFR_HD Vec3 vmax(Vec3 a, Vec3 b) {
    return {fmaxFast(a.x, b.x), fmaxFast(a.y, b.y), fmaxFast(a.z, b.z)};
}
BMFR_HD Vec3 clamp(Vec3 v, Vec3 lo, Vec3 hi) {
    return vmin(vmax(v, lo), hi);
}
BMFR_HD Vec3 lerp(Vec3 a, Vec3 b, float t) {
    return (1.0f - t) * a + t * b;
}

BMFR_HD Vec3 load3(const float* p, long i) {
    return {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
}
/// RGB of pixel i in a 4-channel (RGB + one more) buffer.
BMFR_HD Vec3 load3Stride4(const float* p, long i) {
    return {p[4 * i], p[4 * i + 1], p[4 * i + 2]};
}
BMFR_HD void store3(float* p, long i, Vec3 v) {
    p[3 * i] = v.x;
    p[3 * i + 1] = v.y;
    p[3 * i + 2] = v.z;
}

} // namespace bmfr
