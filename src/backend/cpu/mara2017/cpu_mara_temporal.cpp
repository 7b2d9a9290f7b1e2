#include "backend/cpu/mara2017/cpu_mara_temporal.h"
#include "backend/cpu/modulation8.h"
#include "backend/cpu/pixel_input8.h"
#include "backend/cpu/reproject8.h"
#include <algorithm>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// Counts the non-finite lanes of the first n values of a plane, as finiteOrZero does.
BMFR_SIMD_INLINE void countNonFinite(const float* plane, long i, int n, int64_t& bad) {
    if (plane) bad += countLanes(~finite8(loadFirst(plane + i, n)));
}

BMFR_SIMD_INLINE void inputGroup(const MaraFrame& f, int x, int y, int n, int64_t& bad) {
    const long i = long(y) * f.width + x;
    const Inputs8 px = readInputs8(f.in, f.modes, i, n, bad);
    f8 m[3] = {px.color[0], px.color[1], px.color[2]};
    if (f.in.matteIndirect) {
        loadXyz8(f.in.matteIndirect + 3 * i, n, m);
        finiteOrZero8(m, bad);
    }
    for (f8& v : m) v = max8(v, f8{});
    storeXyz8(f.matte + 3 * i, n, m);
    if (f.glossy) {
        f8 g[3];
        loadXyz8(f.in.glossyIndirect + 3 * i, n, g);
        finiteOrZero8(g, bad);
        for (f8& v : g) v = max8(v, f8{});
        storeXyz8(f.glossySignal + 3 * i, n, g);
    }
    storeXyz8(f.position + 3 * i, n, px.position);
    storeXyz8(f.normal + 3 * i, n, px.normal);
    // The buffers read later are counted here, once.
    f8 unused[3];
    for (const float* p : {f.in.directLight, f.in.specularF0}) {
        if (!p) continue;
        loadXyz8(p + 3 * i, n, unused);
        finiteOrZero8(unused, bad);
    }
    countNonFinite(f.in.roughness, i, n, bad);
    countNonFinite(f.in.glossyHitDistance, i, n, bad);
    Surface8 was;
    previousSurface8(f.in, f.previous, i, x, y, n, px.position, px.normal, bad, was);
    storeXyz8(f.expected + 3 * i, n, was.position);
    storeXy8(f.previousPixel + 2 * i, n, was.px, was.py);
}

/// maraConfidence for eight distances.
BMFR_SIMD_INLINE f8 confidence8(f8 distance, float h, float d0, float d1) {
    f8 t = (distance - d0) / (d1 - d0);
    t = t < 0.0f ? f8{} : (t > 1.0f ? splat8(1.0f) : t);
    const f8 s = t * t * (3.0f - 2.0f * t);
    const f8 c = h * (1.0f - s);
    return distance >= 0.0f ? c : f8{}; // NaN: no history
}

/// v clamped per channel to maraBox of `signal` around each of the n pixels from column x of
/// row y: eight at once where the boxes' columns are inside the image.
BMFR_SIMD_INLINE void clampToBox8(const MaraFrame& f, const float* signal, int x, int y, int n,
                                  f8 v[3]) {
    const int r = f.clampRadius;
    f8 lo[3], hi[3];
    if (x - r >= 0 && x + 8 + r <= f.width) {
        for (int c = 0; c < 3; ++c) lo[c] = splat8(INFINITY), hi[c] = splat8(-INFINITY);
        for (int qy = std::max(0, y - r); qy <= std::min(f.height - 1, y + r); ++qy)
            for (int dx = -r; dx <= r; ++dx) {
                f8 q[3];
                deinterleave3(signal + 3 * (long(qy) * f.width + x + dx), q[0], q[1], q[2]);
                for (int c = 0; c < 3; ++c) lo[c] = min8(lo[c], q[c]), hi[c] = max8(hi[c], q[c]);
            }
    } else {
        for (int l = 0; l < n; ++l) {
            Vec3 a, b;
            maraBox(signal, f.width, f.height, x + l, y, r, a, b);
            lo[0][l] = a.x, lo[1][l] = a.y, lo[2][l] = a.z;
            hi[0][l] = b.x, hi[1][l] = b.y, hi[2][l] = b.z;
        }
    }
    for (int c = 0; c < 3; ++c) v[c] = min8(max8(v[c], lo[c]), hi[c]);
}

/// maraHistoryWeight for eight lanes: c, or at most n / (n + 1) with the cumulative start.
BMFR_SIMD_INLINE f8 historyWeight8(const MaraFrame& f, f8 c, f8 n) {
    if (!f.cumulativeStart) return c;
    const f8 mean = n / (n + 1.0f);
    return c < mean ? c : mean;
}

BMFR_SIMD_INLINE void temporalGroup(const MaraFrame& f, int x, int y, int n) {
    const long i = long(y) * f.width + x;
    f8 m[3], px, py;
    loadXyz8(f.matte + 3 * i, n, m);
    loadXy8(f.previousPixel + 2 * i, n, px, py);
    const i8 valid = (px > -1e5f) & firstLanes(n);
    f8 t[3] = {m[0], m[1], m[2]}, c{}, samples = splat8(1.0f);
    i8 accept{};
    if (anyLane(valid)) {
        const Footprint8 fp = footprint8(px, py);
        const Taps8 taps = taps8(fp, f.width, f.height, valid);
        f8 expected[3];
        loadXyz8(f.expected + 3 * i, n, expected);
        i8 ok[4], count[4];
        f8 weight[4];
        forTaps(taps, [&] [[gnu::always_inline]] () {
            for (int k = 0; k < 4; ++k) {
                f8 q[3];
                tapXyz(taps, f.prevPosition, k, q);
                for (int ch = 0; ch < 3; ++ch) q[ch] = q[ch] - expected[ch];
                f8 distance = (q[0] * q[0] + q[1] * q[1]) + q[2] * q[2];
                for (int l = 0; l < 8; ++l) distance[l] = __builtin_sqrtf(distance[l]);
                const f8 ck = confidence8(distance, f.h, f.d0, f.d1);
                count[k] = tapBytes(taps, f.prevCount, k);
                ok[k] = valid & taps.inside[k] & (count[k] != 0) & (ck > 0.0f);
                weight[k] = fp.weight[k] * ck;
                accept |= ok[k] & (1 << k);
            }
        });
        f8 sum[3];
        c = weightedTaps<3>(
            taps, weight, ok, [&](int k, f8* v) { tapXyz(taps, f.prevMatte, k, v); }, sum);
        // The nearest tap: the first of the largest weights.
        f8 best{}, nearest{};
        for (int k = 0; k < 4; ++k) {
            const i8 more = ok[k] & (weight[k] > best);
            best = more ? weight[k] : best;
            nearest = more ? __builtin_convertvector(count[k], f8) : nearest;
        }
        const i8 history = c > 0.0f;
        if (anyLane(history)) {
            const f8 safe = history ? c : splat8(1.0f);
            f8 hist[3];
            for (int ch = 0; ch < 3; ++ch) hist[ch] = sum[ch] / safe;
            if (f.clampHistory) clampToBox8(f, f.matte, x, y, n, hist);
            const f8 w = historyWeight8(f, c, nearest);
            for (int ch = 0; ch < 3; ++ch) t[ch] = history ? lerp8(m[ch], hist[ch], w) : m[ch];
            samples = history ? min8(nearest + 1.0f, splat8(255.0f)) : samples;
        }
    }
    storeXyz8(f.temporal + 3 * i, n, t);
    storeFirst(f.confidence + i, c, n);
    storeBytes(f.accept + i, accept, n);
    storeBytes(f.count + i, __builtin_convertvector(samples, i8), n);
}

/// Stage 8 for the n <= 8 pixels from column x of row y.
BMFR_SIMD_INLINE void glossyGroup(const MaraFrame& f, int x, int y, int n) {
    const long i = long(y) * f.width + x;
    f8 g[3];
    const f8 c = loadFirst(f.confidence + i, n);
    loadXyz8(f.glossySignal + 3 * i, n, g);
    f8 t[3] = {g[0], g[1], g[2]};
    const i8 active = (c > 0.0f) & firstLanes(n);
    if (anyLane(active)) {
        f8 px, py;
        loadXy8(f.previousPixel + 2 * i, n, px, py);
        if (f.virtualReprojection && f.in.glossyHitDistance) {
            // maraVirtualPreviousPixel: the virtual position X + d (X - eye) / |X - eye|.
            const f8 d = loadFirst(f.in.glossyHitDistance + i, n);
            f8 p[3], v[3];
            loadXyz8(f.position + 3 * i, n, p);
            const float eye[3] = {f.eye.x, f.eye.y, f.eye.z};
            for (int ch = 0; ch < 3; ++ch) v[ch] = p[ch] - eye[ch];
            f8 len = (v[0] * v[0] + v[1] * v[1]) + v[2] * v[2];
            for (int l = 0; l < 8; ++l) len[l] = __builtin_sqrtf(len[l]);
            const f8 s = d / len;
            f8 q[3];
            for (int ch = 0; ch < 3; ++ch) q[ch] = p[ch] + s * v[ch];
            f8 vx, vy;
            const i8 projected = project8(q, f.previous.viewProjection, f.previous.jitter, f.width,
                                          f.height, vx, vy);
            const i8 ok = finite8(d) & (d >= 0.0f) & (len > 0.0f) & projected;
            px = ok ? vx : px, py = ok ? vy : py;
        }
        // maraBilinear: the taps inside the image with a positive weight, renormalised.
        const Footprint8 fp = footprint8(px, py);
        const Taps8 taps = taps8(fp, f.width, f.height, active);
        i8 use[4];
        for (int k = 0; k < 4; ++k) use[k] = active & taps.inside[k] & (fp.weight[k] > 0.0f);
        f8 sum[3];
        const f8 total = weightedTaps<3>(
            taps, fp.weight, use, [&](int k, f8* v) { tapXyz(taps, f.prevGlossy, k, v); }, sum);
        const i8 history = active & (total > 0.0f);
        if (anyLane(history)) {
            const f8 safe = history ? total : splat8(1.0f);
            f8 hist[3];
            for (int ch = 0; ch < 3; ++ch) hist[ch] = sum[ch] / safe;
            if (f.clampHistory) clampToBox8(f, f.glossySignal, x, y, n, hist);
            const f8 count = __builtin_convertvector(loadBytes(f.count + i, n), f8);
            const f8 w = historyWeight8(f, c, count - 1.0f);
            for (int ch = 0; ch < 3; ++ch) t[ch] = history ? lerp8(g[ch], hist[ch], w) : g[ch];
        }
    }
    storeXyz8(f.glossyTemporal + 3 * i, n, t);
    storeXyz8(f.glossyHistory + 3 * i, n, t);
}

/// maraComposePixel of the n <= 8 pixels from i, in its order of operations.
BMFR_SIMD_INLINE void composeGroup(const MaraFrame& f, long i, int n) {
    f8 m[3];
    loadXyz8(f.matteOut + 3 * i, n, m);
    if (!f.factored) {
        remodulate8(m, f.in, i, n, true, f.modes.albedoEpsilon);
        storeXyz8(f.composed + 3 * i, n, m);
        return;
    }
    int64_t unused = 0; // counted in maraInputPixel
    auto finiteOf = [&](const float* plane, f8 v[3]) __attribute__((always_inline)) {
        if (plane) {
            loadXyz8(plane + 3 * i, n, v);
            finiteOrZero8(v, unused);
        } else {
            v[0] = v[1] = v[2] = f8{};
        }
    };
    f8 albedo[3], direct[3], emission[3], g[3] = {}, fresnel[3] = {};
    finiteOf(f.in.albedo, albedo);
    for (f8& v : albedo) v = max8(v, f8{}); // vmax(albedo, 0): its comparison, b when a < b
    if (f.in.specularF0) {
        f8 p[3], nrm[3], f0[3];
        loadXyz8(f.position + 3 * i, n, p);
        loadXyz8(f.normal + 3 * i, n, nrm);
        const f8 v[3] = {f.eye.x - p[0], f.eye.y - p[1], f.eye.z - p[2]};
        f8 len = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        for (int l = 0; l < 8; ++l) len[l] = __builtin_sqrtf(len[l]);
        const f8 d = nrm[0] * v[0] + nrm[1] * v[1] + nrm[2] * v[2];
        const f8 cosine = len > 0.0f ? abs8(d) / len : splat8(1.0f);
        finiteOf(f.in.specularF0, f0);
        for (f8& c : f0) c = max8(c, f8{});
        // maraFresnel
        const f8 clamped = cosine > 0.0f ? (cosine < 1.0f ? cosine : splat8(1.0f)) : f8{};
        const f8 mm = 1.0f - clamped, m2 = mm * mm, k = m2 * m2 * mm;
        for (int c = 0; c < 3; ++c) fresnel[c] = f0[c] + k * (1.0f - f0[c]);
    }
    if (f.glossy) loadXyz8(f.glossyOut + 3 * i, n, g);
    finiteOf(f.in.directLight, direct);
    finiteOf(f.in.emission, emission);
    f8 out[3];
    for (int c = 0; c < 3; ++c) { // maraCompose
        const f8 one = 1.0f - fresnel[c];
        out[c] = direct[c] + one * one * albedo[c] * m[c] + fresnel[c] * g[c] + emission[c];
    }
    storeXyz8(f.composed + 3 * i, n, out);
}

BMFR_SIMD_DISPATCH(void, composeRows, (const MaraFrame& f, long y0, long y1), (f, y0, y1)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8)
            composeGroup(f, y * f.width + x, std::min(8, f.width - x));
}

BMFR_SIMD_DISPATCH(void, glossyRows, (const MaraFrame& f, long y0, long y1), (f, y0, y1)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8) glossyGroup(f, x, int(y), std::min(8, f.width - x));
}

BMFR_SIMD_DISPATCH(void, inputRows, (const MaraFrame& f, long y0, long y1, int64_t& bad),
                   (f, y0, y1, bad)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8)
            inputGroup(f, x, int(y), std::min(8, f.width - x), bad);
}

BMFR_SIMD_DISPATCH(void, temporalRows, (const MaraFrame& f, long y0, long y1), (f, y0, y1)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; x += 8) temporalGroup(f, x, int(y), std::min(8, f.width - x));
}

} // namespace

int64_t maraInputRows(const MaraFrame& f, long y0, long y1) {
    int64_t bad = 0;
    inputRows(f, y0, y1, bad);
    return bad;
}

void maraMatteTemporalRows(const MaraFrame& f, long y0, long y1) {
    temporalRows(f, y0, y1);
}

void maraGlossyTemporalRows(const MaraFrame& f, long y0, long y1) {
    glossyRows(f, y0, y1);
}

void maraComposeRows(const MaraFrame& f, long y0, long y1) {
    composeRows(f, y0, y1);
}

} // namespace bmfr::cpu
