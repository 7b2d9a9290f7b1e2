// Four- and eight-wide float vectors (GCC/Clang vector extensions) for the fast CPU passes.
// Portable source: the compiler lowers them to SSE, AVX2 or NEON for each target clone.
#pragma once
#include <cstdint>
#include <cstring>

namespace bmfr::simd {

typedef float f4 __attribute__((vector_size(16)));
typedef int32_t i4 __attribute__((vector_size(16)));
typedef float f8 __attribute__((vector_size(32)));
typedef int32_t i8 __attribute__((vector_size(32)));
typedef uint8_t u8x8 __attribute__((vector_size(8)));

#define BMFR_SIMD_INLINE [[gnu::always_inline]] inline

// Hot kernels are compiled twice, for x86-64-v3 (AVX2 + FMA) and the baseline, and the loader
// picks one at run time. Within one machine the choice is fixed, so output bits are repeatable.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define BMFR_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define BMFR_SIMD_CLONES
#endif

BMFR_SIMD_INLINE f4 load4(const float* p) {
    f4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
BMFR_SIMD_INLINE void store4(float* p, f4 v) {
    std::memcpy(p, &v, sizeof v);
}
BMFR_SIMD_INLINE f8 load8(const float* p) {
    f8 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
BMFR_SIMD_INLINE void store8(float* p, f8 v) {
    std::memcpy(p, &v, sizeof v);
}
/// Lane masks (comparison results: -1 true, 0 false), reduced through shuffles.
BMFR_SIMD_INLINE bool allLanes(i8 m) {
    m &= __builtin_shuffle(m, i8{4, 5, 6, 7, 0, 1, 2, 3});
    m &= __builtin_shuffle(m, i8{2, 3, 0, 1, 6, 7, 4, 5});
    m &= __builtin_shuffle(m, i8{1, 0, 3, 2, 5, 4, 7, 6});
    return m[0] != 0;
}
BMFR_SIMD_INLINE bool anyLane(i8 m) {
    m |= __builtin_shuffle(m, i8{4, 5, 6, 7, 0, 1, 2, 3});
    m |= __builtin_shuffle(m, i8{2, 3, 0, 1, 6, 7, 4, 5});
    m |= __builtin_shuffle(m, i8{1, 0, 3, 2, 5, 4, 7, 6});
    return m[0] != 0;
}
/// Number of true lanes.
BMFR_SIMD_INLINE int countLanes(i8 m) {
    m += __builtin_shuffle(m, i8{4, 5, 6, 7, 0, 1, 2, 3});
    m += __builtin_shuffle(m, i8{2, 3, 0, 1, 6, 7, 4, 5});
    m += __builtin_shuffle(m, i8{1, 0, 3, 2, 5, 4, 7, 6});
    return -m[0];
}
/// Smallest lane.
BMFR_SIMD_INLINE int hminLanes(i8 v) {
    v = v < __builtin_shuffle(v, i8{4, 5, 6, 7, 0, 1, 2, 3})
            ? v
            : __builtin_shuffle(v, i8{4, 5, 6, 7, 0, 1, 2, 3});
    v = v < __builtin_shuffle(v, i8{2, 3, 0, 1, 6, 7, 4, 5})
            ? v
            : __builtin_shuffle(v, i8{2, 3, 0, 1, 6, 7, 4, 5});
    return v[0] < v[1] ? v[0] : v[1];
}
/// Lanes 0 .. n-1 true.
BMFR_SIMD_INLINE i8 firstLanes(int n) {
    const i8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    return lane < n;
}

/// Eight packed xyz records (24 floats) as x, y and z lanes, and back.
BMFR_SIMD_INLINE void deinterleave3(const float* p, f8& x, f8& y, f8& z) {
    const f8 a = load8(p), b = load8(p + 8), c = load8(p + 16);
    x = __builtin_shuffle(__builtin_shuffle(a, b, i8{0, 3, 6, 9, 12, 15, 0, 0}), c,
                          i8{0, 1, 2, 3, 4, 5, 10, 13});
    y = __builtin_shuffle(__builtin_shuffle(a, b, i8{1, 4, 7, 10, 13, 0, 0, 0}), c,
                          i8{0, 1, 2, 3, 4, 8, 11, 14});
    z = __builtin_shuffle(__builtin_shuffle(a, b, i8{2, 5, 8, 11, 14, 0, 0, 0}), c,
                          i8{0, 1, 2, 3, 4, 9, 12, 15});
}
BMFR_SIMD_INLINE void interleave3(f8 x, f8 y, f8 z, float* p) {
    store8(p, __builtin_shuffle(__builtin_shuffle(x, y, i8{0, 8, 0, 1, 9, 0, 2, 10}), z,
                                i8{0, 1, 8, 3, 4, 9, 6, 7}));
    store8(p + 8, __builtin_shuffle(__builtin_shuffle(x, y, i8{0, 3, 11, 0, 4, 12, 0, 5}), z,
                                    i8{10, 1, 2, 11, 4, 5, 12, 7}));
    store8(p + 16, __builtin_shuffle(__builtin_shuffle(x, y, i8{13, 0, 6, 14, 0, 7, 15, 0}), z,
                                     i8{0, 13, 2, 3, 14, 5, 6, 15}));
}
/// The first n (1 to 8) packed xyz records; lanes n to 7 read as 0.
BMFR_SIMD_INLINE void loadXyz8(const float* p, int n, f8 out[3]) {
    if (n == 8) return deinterleave3(p, out[0], out[1], out[2]);
    float staged[24] = {};
    std::memcpy(staged, p, sizeof(float) * 3 * size_t(n));
    deinterleave3(staged, out[0], out[1], out[2]);
}
/// Stores the first n (1 to 8) records as packed xyz.
BMFR_SIMD_INLINE void storeXyz8(float* p, int n, const f8 v[3]) {
    if (n == 8) return interleave3(v[0], v[1], v[2], p);
    float staged[24];
    interleave3(v[0], v[1], v[2], staged);
    std::memcpy(p, staged, sizeof(float) * 3 * size_t(n));
}
/// Stores the first n (1 to 8) lanes.
BMFR_SIMD_INLINE void storeFirst(float* p, f8 v, int n) {
    if (n == 8) return store8(p, v);
    std::memcpy(p, &v, sizeof(float) * size_t(n));
}
/// base[index[l]] for each lane.
BMFR_SIMD_INLINE f8 gather8(const float* base, i8 index) {
    float lanes[8];
    for (int l = 0; l < 8; ++l) lanes[l] = base[index[l]];
    return load8(lanes);
}
/// Unnormalised YCoCg of bmfr::rgbToYCoCg for eight pixels, and back, with the same roundings.
BMFR_SIMD_INLINE void rgbToYCoCg8(const f8 c[3], f8 out[3]) {
    out[0] = (c[0] + 2.0f * c[1]) + c[2];
    out[1] = 2.0f * c[0] - 2.0f * c[2];
    out[2] = (2.0f * c[1] - c[0]) - c[2];
}
BMFR_SIMD_INLINE void yCoCgToRgb8(const f8 c[3], f8 out[3]) {
    out[0] = 0.25f * ((c[0] + c[1]) - c[2]);
    out[1] = 0.25f * (c[0] + c[2]);
    out[2] = 0.25f * ((c[0] - c[1]) - c[2]);
}

/// x, y, z of a packed 3-float record, w = 0. `last` marks the final record of a buffer, where
/// a 16-byte load would read past the end.
BMFR_SIMD_INLINE f4 loadXyz(const float* p, bool last) {
    if (last) return f4{p[0], p[1], p[2], 0.0f};
    f4 v = load4(p);
    v[3] = 0.0f;
    return v;
}
BMFR_SIMD_INLINE f4 splat4(float a) {
    return f4{a, a, a, a};
}
BMFR_SIMD_INLINE f8 splat8(float a) {
    return f8{a, a, a, a, a, a, a, a};
}
BMFR_SIMD_INLINE f4 min4(f4 a, f4 b) {
    return b < a ? b : a;
}
BMFR_SIMD_INLINE f4 max4(f4 a, f4 b) {
    return a < b ? b : a;
}
BMFR_SIMD_INLINE f8 min8(f8 a, f8 b) {
    return b < a ? b : a;
}
BMFR_SIMD_INLINE f8 max8(f8 a, f8 b) {
    return a < b ? b : a;
}
/// a.x*b.x + a.y*b.y + a.z*b.z, summed in that order.
BMFR_SIMD_INLINE float dot3(f4 a, f4 b) {
    const f4 m = a * b;
    return m[0] + m[1] + m[2];
}
/// Sum of the eight lanes, as a fixed tree (repeatable).
BMFR_SIMD_INLINE float hsum8(f8 v) {
    return ((v[0] + v[4]) + (v[1] + v[5])) + ((v[2] + v[6]) + (v[3] + v[7]));
}
BMFR_SIMD_INLINE float hmin8(f8 v) {
    float m = v[0];
    for (int i = 1; i < 8; ++i) m = v[i] < m ? v[i] : m;
    return m;
}
BMFR_SIMD_INLINE float hmax8(f8 v) {
    float m = v[0];
    for (int i = 1; i < 8; ++i) m = m < v[i] ? v[i] : m;
    return m;
}
/// (1 - t) a + t b, as bmfr::lerp.
BMFR_SIMD_INLINE f4 lerp4(f4 a, f4 b, float t) {
    return (1.0f - t) * a + t * b;
}
/// Lanes x, y, z all finite.
BMFR_SIMD_INLINE bool finiteXyz(f4 v) {
    const i4 ok = (v - v) == 0.0f;
    return (ok[0] & ok[1] & ok[2]) != 0;
}
/// Non-finite lanes among x, y, z replaced by 0 and counted in `bad`; w set to 0.
BMFR_SIMD_INLINE f4 finiteOrZero4(f4 v, int64_t& bad) {
    v[3] = 0.0f;
    if (__builtin_expect(finiteXyz(v), 1)) return v;
    const i4 ok = (v - v) == 0.0f;
    bad += 3 + ok[0] + ok[1] + ok[2]; // ok lanes are -1
    return ok ? v : f4{};
}
/// The unnormalised YCoCg of bmfr::rgbToYCoCg, and back; w is passed through as 0.
/// As matrix columns times broadcast channels; the products by 1, 2 and 0.25 are exact, so the
/// sums round as in the scalar forms.
BMFR_SIMD_INLINE f4 rgbToYCoCg4(f4 c) {
    const f4 r = __builtin_shuffle(c, i4{0, 0, 0, 0}), g = __builtin_shuffle(c, i4{1, 1, 1, 1}),
             b = __builtin_shuffle(c, i4{2, 2, 2, 2});
    return (r * f4{1, 2, -1, 0} + g * f4{2, 0, 2, 0}) + b * f4{1, -2, -1, 0};
}
BMFR_SIMD_INLINE f4 yCoCgToRgb4(f4 c) {
    const f4 y = __builtin_shuffle(c, i4{0, 0, 0, 0}), co = __builtin_shuffle(c, i4{1, 1, 1, 1}),
             cg = __builtin_shuffle(c, i4{2, 2, 2, 2});
    return 0.25f * ((y + co * f4{1, 0, -1, 0}) + cg * f4{-1, 1, -1, 0});
}

/// For four vectors whose lanes 3 and 7 are zero: lanes 0-3 = (a0+a1)+(a2+a3) of a, b, c, d
/// and lanes 4-7 = (a4+a5)+(a6+a7) of each, i.e. x, y, z summed in dot3's order.
BMFR_SIMD_INLINE f8 sum3Of4(f8 a, f8 b, f8 c, f8 d) {
    const i8 even = {0, 8, 2, 10, 4, 12, 6, 14}, odd = {1, 9, 3, 11, 5, 13, 7, 15};
    const f8 ab = __builtin_shuffle(a, b, even) + __builtin_shuffle(a, b, odd);
    const f8 cd = __builtin_shuffle(c, d, even) + __builtin_shuffle(c, d, odd);
    const i8 lo = {0, 1, 8, 9, 4, 5, 12, 13}, hi = {2, 3, 10, 11, 6, 7, 14, 15};
    return __builtin_shuffle(ab, cd, lo) + __builtin_shuffle(ab, cd, hi);
}

/// In-place transpose of an 8x8 block held as eight rows.
BMFR_SIMD_INLINE void transpose8x8(f8 r[8]) {
    const i8 lo = {0, 8, 1, 9, 4, 12, 5, 13}, hi = {2, 10, 3, 11, 6, 14, 7, 15};
    const i8 pairLo = {0, 1, 8, 9, 4, 5, 12, 13}, pairHi = {2, 3, 10, 11, 6, 7, 14, 15};
    const i8 halfLo = {0, 1, 2, 3, 8, 9, 10, 11}, halfHi = {4, 5, 6, 7, 12, 13, 14, 15};
    f8 t[8], u[8];
    for (int k = 0; k < 4; ++k) {
        t[2 * k] = __builtin_shuffle(r[2 * k], r[2 * k + 1], lo);
        t[2 * k + 1] = __builtin_shuffle(r[2 * k], r[2 * k + 1], hi);
    }
    for (int k = 0; k < 2; ++k) {
        u[4 * k] = __builtin_shuffle(t[4 * k], t[4 * k + 2], pairLo);
        u[4 * k + 1] = __builtin_shuffle(t[4 * k], t[4 * k + 2], pairHi);
        u[4 * k + 2] = __builtin_shuffle(t[4 * k + 1], t[4 * k + 3], pairLo);
        u[4 * k + 3] = __builtin_shuffle(t[4 * k + 1], t[4 * k + 3], pairHi);
    }
    for (int k = 0; k < 4; ++k) {
        r[k] = __builtin_shuffle(u[k], u[k + 4], halfLo);
        r[k + 4] = __builtin_shuffle(u[k], u[k + 4], halfHi);
    }
}

} // namespace bmfr::simd
