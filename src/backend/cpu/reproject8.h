// Reprojection of eight pixels at once (SIMD across pixels): the previous-frame pixel and the
// bilinear footprint of each, from packed xyz positions. The same math as core/reprojection.h.
#pragma once
#include "core/mat4.h"
#include "core/reprojection.h"
#include "core/simd.h"

namespace bmfr::cpu {

/// One pixel's reprojection: where it was and its bilinear footprint there.
struct Reprojected {
    bool valid = false;          ///< projectToPixel succeeded
    Vec2 pixel{-1e6f, -1e6f};    ///< continuous previous pixel; far outside when not valid
    BilinearFootprint footprint; ///< of `pixel`
};

/// x, y and z lanes of eight packed xyz records (24 floats).
BMFR_SIMD_INLINE void deinterleave3(const float* p, simd::f8& x, simd::f8& y, simd::f8& z) {
    using namespace simd;
    const f8 a = load8(p), b = load8(p + 8), c = load8(p + 16);
    x = __builtin_shuffle(__builtin_shuffle(a, b, i8{0, 3, 6, 9, 12, 15, 0, 0}), c,
                          i8{0, 1, 2, 3, 4, 5, 10, 13});
    y = __builtin_shuffle(__builtin_shuffle(a, b, i8{1, 4, 7, 10, 13, 0, 0, 0}), c,
                          i8{0, 1, 2, 3, 4, 8, 11, 14});
    z = __builtin_shuffle(__builtin_shuffle(a, b, i8{2, 5, 8, 11, 14, 0, 0, 0}), c,
                          i8{0, 1, 2, 3, 4, 9, 12, 15});
}

/// projectToPixel and bilinearFootprint for the eight packed positions at `positions`
/// (non-finite components count as 0, as the per-pixel input reader makes them).
BMFR_SIMD_INLINE void reproject8(const float* positions, const Mat4& m, const float jitter[2],
                                 int width, int height, Reprojected out[8]) {
    using namespace simd;
    f8 x, y, z;
    deinterleave3(positions, x, y, z);
    x = (x - x) == 0.0f ? x : f8{}, y = (y - y) == 0.0f ? y : f8{}, z = (z - z) == 0.0f ? z : f8{};
    const f8 cx = m.m[0][0] * x + m.m[0][1] * y + m.m[0][2] * z + m.m[0][3];
    const f8 cy = m.m[1][0] * x + m.m[1][1] * y + m.m[1][2] * z + m.m[1][3];
    const f8 cw = m.m[3][0] * x + m.m[3][1] * y + m.m[3][2] * z + m.m[3][3];
    f8 px = (cx / cw * 0.5f + 0.5f) * float(width) - 0.5f - jitter[0];
    f8 py = (cy / cw * 0.5f + 0.5f) * float(height) - 0.5f - jitter[1];
    // NaN fails every comparison, so the finite test is folded into the range test.
    const f8 big = splat8(1e8f);
    const i8 valid = (cw > 0.0f) & (px < big) & (px > -big) & (py < big) & (py > -big);
    px = valid ? px : splat8(-1e6f), py = valid ? py : splat8(-1e6f);
    // floor() through truncation: exact for |v| < 2^31.
    f8 fx = __builtin_convertvector(__builtin_convertvector(px, i8), f8);
    f8 fy = __builtin_convertvector(__builtin_convertvector(py, i8), f8);
    fx = fx > px ? fx - 1.0f : fx, fy = fy > py ? fy - 1.0f : fy;
    const f8 ax = px - fx, ay = py - fy;
    const f8 w0 = (1 - ax) * (1 - ay), w1 = ax * (1 - ay), w2 = (1 - ax) * ay, w3 = ax * ay;
    const i8 ix = __builtin_convertvector(fx, i8), iy = __builtin_convertvector(fy, i8);
    for (int l = 0; l < 8; ++l) {
        Reprojected& r = out[l];
        r.valid = valid[l] != 0;
        r.pixel = {px[l], py[l]};
        r.footprint.x0 = ix[l], r.footprint.y0 = iy[l];
        r.footprint.weight[0] = w0[l], r.footprint.weight[1] = w1[l];
        r.footprint.weight[2] = w2[l], r.footprint.weight[3] = w3[l];
    }
}

/// The same for one pixel (row tails).
BMFR_SIMD_INLINE Reprojected reprojectOne(Vec3 p, const Mat4& m, const float jitter[2], int width,
                                          int height) {
    Reprojected r;
    r.valid = projectToPixel(m, p, jitter, width, height, r.pixel);
    if (!r.valid) r.pixel = {-1e6f, -1e6f};
    r.footprint = bilinearFootprint(r.pixel);
    return r;
}

} // namespace bmfr::cpu
