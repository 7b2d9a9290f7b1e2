// Reprojection and bilinear taps of eight pixels at once (SIMD across pixels), shared by phase
// I, phase III and TAA. The same math and roundings as core/reprojection.h.
#pragma once
#include "backend/cpu/simd.h"
#include "core/mat4.h"
#include "temporal/history.h"
#include "temporal/reprojection.h"

namespace bmfr::cpu {

/// Where eight surface points were in the previous frame: projectToPixel per lane, with the
/// lanes where it fails moved far outside every image (-1e6), as phase I stores them. Returns
/// the lanes where it succeeds.
BMFR_SIMD_INLINE simd::i8 project8(const simd::f8 p[3], const Mat4& m, const float jitter[2],
                                   int width, int height, simd::f8& px, simd::f8& py) {
    using namespace simd;
    const f8 cx = ((m.m[0][0] * p[0] + m.m[0][1] * p[1]) + m.m[0][2] * p[2]) + m.m[0][3];
    const f8 cy = ((m.m[1][0] * p[0] + m.m[1][1] * p[1]) + m.m[1][2] * p[2]) + m.m[1][3];
    const f8 cw = ((m.m[3][0] * p[0] + m.m[3][1] * p[1]) + m.m[3][2] * p[2]) + m.m[3][3];
    px = (cx / cw * 0.5f + 0.5f) * float(width) - 0.5f - jitter[0];
    py = (cy / cw * 0.5f + 0.5f) * float(height) - 0.5f - jitter[1];
    // NaN fails every comparison, so the finite test is folded into the range test.
    const f8 big = splat8(1e8f);
    const i8 valid = (cw > 0.0f) & (px < big) & (px > -big) & (py < big) & (py > -big);
    px = valid ? px : splat8(-1e6f), py = valid ? py : splat8(-1e6f);
    return valid;
}

/// findPreviousSurface (temporal/reprojection.h) of the n <= 8 pixels [i, i + n) of one row,
/// the first at column x of row y, with current surfaces (p, n): the previous pixels (lanes
/// without one at -1e6), and the positions and normals for the discard test. Returns the lanes
/// with a previous pixel; counts non-finite values in `bad` as the scalar version does.
struct Surface8 {
    simd::f8 px, py;
    simd::f8 position[3], normal[3];
};

BMFR_SIMD_INLINE simd::i8 previousSurface8(const InputPlanes& in, const PreviousFrame& prev, long i,
                                           int x, int y, int n, const simd::f8 p[3],
                                           const simd::f8 nrm[3], int64_t& bad, Surface8& s) {
    using namespace simd;
    for (int c = 0; c < 3; ++c) s.position[c] = p[c], s.normal[c] = nrm[c];
    if (in.previousPosition) {
        loadXyz8(in.previousPosition + 3 * i, n, s.position);
        finiteOrZero8(s.position, bad);
    }
    if (in.previousNormal) {
        loadXyz8(in.previousNormal + 3 * i, n, s.normal);
        finiteOrZero8(s.normal, bad);
    }
    if (in.motion) {
        f8 mx, my;
        loadXy8(in.motion + 2 * i, n, mx, my);
        const i8 okX = finite8(mx), okY = finite8(my);
        bad += countLanes(~okX) + countLanes(~okY);
        const f8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
        s.px = (float(x) + lane) + mx, s.py = float(y) + my;
        const f8 big = splat8(1e8f);
        const i8 valid = okX & okY & (s.px < big) & (s.px > -big) & (s.py < big) & (s.py > -big) &
                         (prev.valid ? firstLanes(n) : i8{});
        s.px = valid ? s.px : splat8(-1e6f), s.py = valid ? s.py : splat8(-1e6f);
        return valid;
    }
    if (!prev.valid) {
        s.px = s.py = splat8(-1e6f);
        return i8{};
    }
    return project8(s.position, prev.viewProjection, prev.jitter, in.width, in.height, s.px, s.py);
}

/// bilinearFootprint of eight continuous pixels: top-left tap and the four tap weights.
struct Footprint8 {
    simd::i8 x0, y0;
    simd::f8 weight[4];
};

BMFR_SIMD_INLINE Footprint8 footprint8(simd::f8 px, simd::f8 py) {
    using namespace simd;
    // floor() through truncation: exact for the |v| < 2^31 that reach here; larger values
    // convert to INT_MIN, which every inside test rejects.
    f8 fx = __builtin_convertvector(__builtin_convertvector(px, i8), f8);
    f8 fy = __builtin_convertvector(__builtin_convertvector(py, i8), f8);
    fx = fx > px ? fx - 1.0f : fx, fy = fy > py ? fy - 1.0f : fy;
    const f8 ax = px - fx, ay = py - fy;
    Footprint8 f;
    f.x0 = __builtin_convertvector(fx, i8), f.y0 = __builtin_convertvector(fy, i8);
    f.weight[0] = (1 - ax) * (1 - ay), f.weight[1] = ax * (1 - ay);
    f.weight[2] = (1 - ax) * ay, f.weight[3] = ax * ay;
    return f;
}

/// The four taps of eight footprints. Coherent: the active lanes' footprints lie side by side
/// in one row pair (x0 = lane + d with d taking at most two neighbouring values, one y0), the
/// common case under smooth motion, so a tap is one or two 8-float loads; inactive lanes (no
/// valid projection, or no accepted tap) read some pixel in the image and must weigh 0.
/// Otherwise per-lane indices clamped into the image. `inside` says which taps are in it.
struct Taps8 {
    bool coherent = false;
    bool split = false; ///< coherent with two values of d: lanes in `upper` read one further
    long at[4] = {};    ///< tap k of lane l is at at[k] + l (+ 1 in `upper`), when coherent
    simd::i8 upper;     ///< lanes with the larger d
    simd::i8 index[4];  ///< clamped tap pixels (not coherent)
    simd::i8 inside[4]; ///< taps in the image
};

BMFR_SIMD_INLINE Taps8 taps8(const Footprint8& f, int width, int height, simd::i8 active) {
    using namespace simd;
    Taps8 t;
    const i8 lane = {0, 1, 2, 3, 4, 5, 6, 7}, big = i8{} + (1 << 30);
    const i8 d = f.x0 - lane;
    const int dLo = hminLanes(active ? d : big), dHi = -hminLanes(active ? -d : big);
    const int yLo = hminLanes(active ? f.y0 : big), yHi = -hminLanes(active ? -f.y0 : big);
    if (dLo <= dHi && dHi - dLo <= 1 && yLo == yHi && dLo >= 0 && dHi + 8 < width && yLo >= 0 &&
        yLo + 1 < height) {
        t.coherent = true;
        t.split = dHi != dLo;
        t.upper = d == dHi;
        const long base = long(yLo) * width + dLo;
        t.at[0] = base, t.at[1] = base + 1, t.at[2] = base + width, t.at[3] = base + width + 1;
        for (int k = 0; k < 4; ++k) t.inside[k] = active;
        return t;
    }
    for (int k = 0; k < 4; ++k) {
        const i8 x = f.x0 + (k & 1), y = f.y0 + (k >> 1);
        t.inside[k] = (x >= 0) & (y >= 0) & (x < width) & (y < height);
        const i8 cx = x < 0 ? i8{} : (x >= width ? i8{} + (width - 1) : x);
        const i8 cy = y < 0 ? i8{} : (y >= height ? i8{} + (height - 1) : y);
        t.index[k] = cy * width + cx;
    }
    return t;
}

/// Tap k of the eight lanes from a plane of one float (or half) per pixel.
template <class T> BMFR_SIMD_INLINE simd::f8 tapPlane(const Taps8& t, const T* plane, int k) {
    using namespace simd;
    if (!t.coherent) return gather8(plane, t.index[k]);
    const T* p = plane + t.at[k];
    return t.split ? (t.upper ? load8(p + 1) : load8(p)) : load8(p);
}

/// Tap k of the eight lanes from a plane of one byte per pixel (emitter bits, lit classes).
BMFR_SIMD_INLINE simd::i8 tapBytes(const Taps8& t, const uint8_t* plane, int k) {
    using namespace simd;
    if (!t.coherent) {
        i8 v;
        for (int l = 0; l < 8; ++l) v[l] = plane[t.index[k][l]];
        return v;
    }
    const uint8_t* p = plane + t.at[k];
    return t.split ? (t.upper ? loadBytes(p + 1, 8) : loadBytes(p, 8)) : loadBytes(p, 8);
}

/// Runs body() with the taps' addressing mode fixed: two copies of the loop, so the compiler
/// drops the per-load choice between plain loads and per-lane gathers from each.
template <typename Body> BMFR_SIMD_INLINE void forTaps(const Taps8& t, Body&& body) {
    if (t.coherent)
        body();
    else
        body();
}

/// The bilinear sum of C channels over the four taps: sum[c] = sum over k of w_k tap_k[c], and
/// the returned sum of the w_k, where w_k = weight[k] in the lanes of use[k] and 0 elsewhere.
/// A zero weight adds exactly nothing, so this rounds as a sum over the used taps alone.
/// fetch(k, v) loads tap k's C channels into v.
template <int C, typename Fetch>
BMFR_SIMD_INLINE simd::f8 weightedTaps(const Taps8& t, const simd::f8 weight[4],
                                       const simd::i8 use[4], Fetch&& fetch, simd::f8 sum[C]) {
    using namespace simd;
    f8 total{};
    for (int c = 0; c < C; ++c) sum[c] = f8{};
    forTaps(t, [&] [[gnu::always_inline]] () {
        for (int k = 0; k < 4; ++k) {
            f8 v[C];
            fetch(k, v);
            const f8 wt = use[k] ? weight[k] : f8{};
            for (int c = 0; c < C; ++c) sum[c] += wt * v[c];
            total += wt;
        }
    });
    return total;
}

/// Tap k of the eight lanes from packed xyz records (3 floats per pixel).
BMFR_SIMD_INLINE void tapXyz(const Taps8& t, const float* records, int k, simd::f8 out[3]) {
    if (t.coherent) {
        const float* p = records + 3 * t.at[k];
        simd::deinterleave3(p, out[0], out[1], out[2]);
        if (!t.split) return;
        simd::f8 next[3];
        simd::deinterleave3(p + 3, next[0], next[1], next[2]);
        for (int c = 0; c < 3; ++c) out[c] = t.upper ? next[c] : out[c];
        return;
    }
    float lanes[3][8];
    for (int l = 0; l < 8; ++l) {
        const float* r = records + 3 * long(t.index[k][l]);
        lanes[0][l] = r[0], lanes[1][l] = r[1], lanes[2][l] = r[2];
    }
    for (int c = 0; c < 3; ++c) out[c] = simd::load8(lanes[c]);
}

/// Tap k of the eight lanes from packed xy records (2 floats per pixel).
BMFR_SIMD_INLINE void tapXy(const Taps8& t, const float* records, int k, simd::f8& x, simd::f8& y) {
    if (t.coherent) {
        const float* p = records + 2 * t.at[k];
        simd::loadXy8(p, 8, x, y);
        if (!t.split) return;
        simd::f8 nextX, nextY;
        simd::loadXy8(p + 2, 8, nextX, nextY);
        x = t.upper ? nextX : x, y = t.upper ? nextY : y;
        return;
    }
    float lanes[2][8];
    for (int l = 0; l < 8; ++l) {
        const long j = t.index[k][l];
        lanes[0][l] = records[2 * j], lanes[1][l] = records[2 * j + 1];
    }
    x = simd::load8(lanes[0]), y = simd::load8(lanes[1]);
}

} // namespace bmfr::cpu
