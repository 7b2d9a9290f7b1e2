#include "backend/cpu/mara2017/cpu_mara_rows.h"
#include "backend/cpu/simd.h"
#include "filters/mara2017/mara_passes.h"
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

BMFR_SIMD_INLINE void sort2(f8& a, f8& b) {
    const f8 lo = a < b ? a : b, hi = a < b ? b : a;
    a = lo, b = hi;
}

/// Devillard's 19-exchange median of nine, per lane (exact: the same value as any median).
BMFR_SIMD_INLINE f8 median9(f8 p[9]) {
    sort2(p[1], p[2]), sort2(p[4], p[5]), sort2(p[7], p[8]);
    sort2(p[0], p[1]), sort2(p[3], p[4]), sort2(p[6], p[7]);
    sort2(p[1], p[2]), sort2(p[4], p[5]), sort2(p[7], p[8]);
    sort2(p[0], p[3]), sort2(p[5], p[8]), sort2(p[4], p[7]);
    sort2(p[3], p[6]), sort2(p[1], p[4]), sort2(p[2], p[5]);
    sort2(p[4], p[7]), sort2(p[4], p[2]), sort2(p[6], p[4]);
    sort2(p[4], p[2]);
    return p[4];
}

/// maraEdgeWeight for eight taps, operation for operation.
BMFR_SIMD_INLINE f8 edgeWeight8(const f8 nc[3], const f8 pc[3], const f8 nq[3], const f8 pq[3],
                                const MaraEdgeWeights& k) {
    f8 cn = nc[0] * nq[0] + nc[1] * nq[1] + nc[2] * nq[2];
    cn = cn > 0.0f ? cn : 0.0f;
    const f8 c2 = cn * cn;
    f8 w = 1.0f - k.normal * (1.0f - c2 * c2);
    w = w > 0.0f ? w : 0.0f;
    const f8 dp[3] = {pq[0] - pc[0], pq[1] - pc[1], pq[2] - pc[2]};
    const f8 d2 = dp[0] * dp[0] + dp[1] * dp[1] + dp[2] * dp[2];
    f8 a = dp[0] * nq[0] + dp[1] * nq[1] + dp[2] * nq[2];
    f8 b = dp[0] * nc[0] + dp[1] * nc[1] + dp[2] * nc[2];
    a = a < 0.0f ? -a : a, b = b < 0.0f ? -b : b;
    const f8 along = a < b ? b : a;
    f8 root = d2;
    for (int l = 0; l < 8; ++l) root[l] = __builtin_sqrtf(root[l]);
    f8 wp = 1.0f - 2.0f * k.plane * along / root;
    wp = wp > 0.0f ? wp : 0.0f;
    return d2 >= k.planeNearSquared ? w * (wp * wp) : w;
}

/// Lane l's quantity q (0 position, 1 normal, 2 colour) of the tap records index[l]: eight
/// 16-byte loads and a transpose.
BMFR_SIMD_INLINE void loadTaps(const float* taps, i8 index, int q, f8 out[3]) {
    f4 r[8];
    for (int l = 0; l < 8; ++l)
        std::memcpy(&r[l], taps + kMaraTapRecord * long(index[l]) + 4 * q, sizeof(f4));
    const f8 a0 = __builtin_shufflevector(r[0], r[4], 0, 1, 2, 3, 4, 5, 6, 7),
             a1 = __builtin_shufflevector(r[1], r[5], 0, 1, 2, 3, 4, 5, 6, 7),
             a2 = __builtin_shufflevector(r[2], r[6], 0, 1, 2, 3, 4, 5, 6, 7),
             a3 = __builtin_shufflevector(r[3], r[7], 0, 1, 2, 3, 4, 5, 6, 7);
    const f8 t0 = __builtin_shuffle(a0, a1, i8{0, 8, 1, 9, 4, 12, 5, 13}), // x0 x1 y0 y1
        t1 = __builtin_shuffle(a2, a3, i8{0, 8, 1, 9, 4, 12, 5, 13}),      // x2 x3 y2 y3
        t2 = __builtin_shuffle(a0, a1, i8{2, 10, 3, 11, 6, 14, 7, 15}),    // z0 z1 . .
        t3 = __builtin_shuffle(a2, a3, i8{2, 10, 3, 11, 6, 14, 7, 15});    // z2 z3 . .
    out[0] = __builtin_shuffle(t0, t1, i8{0, 1, 8, 9, 4, 5, 12, 13});
    out[1] = __builtin_shuffle(t0, t1, i8{2, 3, 10, 11, 6, 7, 14, 15});
    out[2] = __builtin_shuffle(t2, t3, i8{0, 1, 8, 9, 4, 5, 12, 13});
}

BMFR_SIMD_DISPATCH(void, packRow,
                   (const MaraFrame& f, const float* src, bool guide, float* taps, int y),
                   (f, src, guide, taps, y)) {
    for (long i = long(y) * f.width, end = i + f.width; i < end; ++i) {
        float* r = taps + kMaraTapRecord * i;
        const float* from[3] = {f.position + 3 * i, f.normal + 3 * i, src + 3 * i};
        for (int q = guide ? 0 : 2; q < 3; ++q)
            r[4 * q] = from[q][0], r[4 * q + 1] = from[q][1], r[4 * q + 2] = from[q][2],
                  r[4 * q + 3] = 0.0f;
    }
}

/// The most taps of a sparse stage (the settings' range).
constexpr int kMaxTaps = 256;

BMFR_SIMD_DISPATCH(void, sparseRow,
                   (const MaraFrame& f, const float* tapRecords, bool final, int y, int x0, int x1,
                    const MaraTapTables* tables),
                   (f, tapRecords, final, y, x0, x1, tables)) {
    const int w = f.width, taps = final ? f.finalTaps : f.preTaps;
    const long row = long(y) * w;
    float* dst = final ? f.matteOut : f.matteHistory;
    const i8 lane = {0, 1, 2, 3, 4, 5, 6, 7};
    for (int x = x0; x < x1; x += 8) {
        const int n = x1 - x < 8 ? x1 - x : 8;
        const long i = row + x;
        f8 pc[3], nc[3], sum[3];
        const i8 centre = i8{} + int(i) + (lane < n ? lane : 0);
        loadTaps(tapRecords, centre, 0, pc);
        loadTaps(tapRecords, centre, 1, nc);
        loadTaps(tapRecords, centre, 2, sum);
        // Every lane's taps, tap-major, so that the tap loop reads them as vectors.
        alignas(32) int ox[kMaxTaps * 8], oy[kMaxTaps * 8];
        alignas(32) float og[kMaxTaps * 8], ux[kMaxTaps * 8], uy[kMaxTaps * 8];
        f8 radius, sigma;
        int rotation[8], table[8];
        bool computed = false; // some lane's stage 7 taps are not in the tables
        for (int l = 0; l < 8; ++l) {
            rotation[l] = maraPixelRotation(x + (l < n ? l : 0), y, f.frame, f.seed, final ? 7 : 4);
            radius[l] = l >= n ? 0.0f : final ? f.radius[i + l] : f.preRadius;
            sigma[l] = final ? f.finalSigma * radius[l] : f.preSigma;
            table[l] = -1;
            for (int k = 0; final && tables && k < MaraTapTables::kRadii; ++k)
                if (radius[l] == tables->radius[k]) table[l] = k;
            computed |= final && table[l] < 0;
        }
        for (int l = 0; l < 8; ++l) {
            const int r = rotation[l], t = table[l];
            if (computed) { // then every lane computes its taps, from the spiral's units
                const float* spiral = f.finalSpiral + 2 * taps * r;
                for (int k = 0; k < taps; ++k)
                    ux[8 * k + l] = spiral[2 * k], uy[8 * k + l] = spiral[2 * k + 1];
            } else if (final) {
                const int* offsets = tables->offsets[t].data() + 2 * taps * r;
                const float* gauss = tables->gauss[t].data() + taps * r;
                for (int k = 0; k < taps; ++k)
                    ox[8 * k + l] = offsets[2 * k], oy[8 * k + l] = offsets[2 * k + 1],
                               og[8 * k + l] = gauss[k];
            } else {
                const int* offsets = f.preOffsets + 2 * taps * r;
                for (int k = 0; k < taps; ++k)
                    ox[8 * k + l] = offsets[2 * k], oy[8 * k + l] = offsets[2 * k + 1];
                if (f.preGauss)
                    for (int k = 0; k < taps; ++k) og[8 * k + l] = f.preGauss[taps * r + k];
            }
        }
        const i8 live = (radius >= 0.5f) & (lane < n);
        if (!anyLane(live)) {
            storeXyz8(dst + 3 * i, n, sum);
            continue;
        }
        if (computed || (!final && !f.preGauss))
            for (int k = 0; k < taps; ++k) {
                i8 dx, dy;
                if (final) {
                    // maraTapOffset: unit x radius rounded half to even, as nearbyint, by adding
                    // and taking away 1.5 x 2^23 (exact below 2^22 pixels).
                    const f8 magic = f8{} + 12582912.0f;
                    dx = __builtin_convertvector((load8(ux + 8 * k) * radius + magic) - magic, i8);
                    dy = __builtin_convertvector((load8(uy + 8 * k) * radius + magic) - magic, i8);
                    std::memcpy(ox + 8 * k, &dx, sizeof dx),
                        std::memcpy(oy + 8 * k, &dy, sizeof dy);
                } else {
                    std::memcpy(&dx, ox + 8 * k, sizeof dx),
                        std::memcpy(&dy, oy + 8 * k, sizeof dy);
                }
                const f8 d2 = __builtin_convertvector(dx * dx + dy * dy, f8);
                for (int l = 0; l < 8; ++l) og[8 * k + l] = maraGaussian(d2[l], sigma[l]);
            }
        f8 total = f8{} + 1.0f;
        for (int k = 0; k < taps; ++k) {
            i8 dx, dy;
            std::memcpy(&dx, ox + 8 * k, sizeof dx), std::memcpy(&dy, oy + 8 * k, sizeof dy);
            const f8 g = load8(og + 8 * k);
            const i8 qx = x + lane + dx, qy = y + dy;
            const i8 inside = live & (qx >= 0) & (qy >= 0) & (qx < w) & (qy < f.height);
            if (!anyLane(inside)) continue;
            const i8 j = inside ? qy * w + qx : i8{} + int(i);
            f8 pq[3], nq[3], s[3];
            loadTaps(tapRecords, j, 0, pq);
            loadTaps(tapRecords, j, 1, nq);
            loadTaps(tapRecords, j, 2, s);
            f8 wt = g * edgeWeight8(nc, pc, nq, pq, f.edges);
            wt = inside & (wt > 0.0f) ? wt : 0.0f;
            for (int c = 0; c < 3; ++c) sum[c] = sum[c] + wt * s[c];
            total = total + wt;
        }
        const f8 out[3] = {sum[0] / total, sum[1] / total, sum[2] / total};
        storeXyz8(dst + 3 * i, n, out);
    }
}

BMFR_SIMD_DISPATCH(void, medianRow, (const MaraFrame& f, int y), (f, y)) {
    const int w = f.width;
    int rows[3];
    for (int d = -1; d <= 1; ++d)
        rows[d + 1] = y + d < 0 ? 0 : y + d >= f.height ? f.height - 1 : y + d;
    int x = 0;
    if (w >= 10) {
        maraMedianPixel(f, 0, y);
        for (x = 1; x + 8 < w; x += 8) {
            f8 v[3][9];
            for (int r = 0; r < 3; ++r)
                for (int dx = -1; dx <= 1; ++dx) {
                    f8 c[3];
                    deinterleave3(f.temporal + 3 * (long(rows[r]) * w + x + dx), c[0], c[1], c[2]);
                    for (int ch = 0; ch < 3; ++ch) v[ch][3 * r + dx + 1] = c[ch];
                }
            const f8 m[3] = {median9(v[0]), median9(v[1]), median9(v[2])};
            interleave3(m[0], m[1], m[2], f.median + 3 * (long(y) * w + x));
        }
    }
    for (; x < w; ++x) maraMedianPixel(f, x, y);
}

BMFR_SIMD_DISPATCH(void, glossyRow,
                   (const MaraFrame& f, const float* src, float* dst, int y, int dx, int dy),
                   (f, src, dst, y, dx, dy)) {
    const int w = f.width;
    const long row = long(y) * w;
    float g[64];
    int x = 0;
    while (x < w) {
        const long i = row + x;
        const float rough = f.in.roughness ? f.in.roughness[i] : 1.0f;
        bool shared = x + 8 <= w;
        for (int l = 1; shared && l < 8; ++l)
            shared = !f.in.roughness || std::memcmp(&f.in.roughness[i + l], &rough, 4) == 0;
        const float sigma = maraGlossySigma(std::isfinite(rough) ? rough : 1.0f, f.glossyScale,
                                            f.glossyExponent, f.glossyEpsilon);
        const int reach = shared ? int(std::ceil(f.glossyTapSigmas * sigma)) : 0;
        // Eight at once when they share a sigma and, along a row, every tap is inside.
        if (!shared || reach > 63 || (dx && (x - reach < 0 || x + 7 + reach >= w))) {
            const int end = shared ? x + 8 : x + 1;
            for (; x < end; ++x) maraGlossyPassPixel(f, src, dst, x, y, dx, dy);
            continue;
        }
        f8 pc[3], nc[3], sum[3];
        deinterleave3(f.position + 3 * i, pc[0], pc[1], pc[2]);
        deinterleave3(f.normal + 3 * i, nc[0], nc[1], nc[2]);
        deinterleave3(src + 3 * i, sum[0], sum[1], sum[2]);
        f8 total = f8{} + 1.0f;
        int taps = 0;
        for (int k = 1; k <= reach; ++k, ++taps) {
            g[k] = maraGaussian(float(k * k), sigma);
            if (!(g[k] > 0)) break;
        }
        for (int k = 1; k <= taps; ++k)
            for (int side = -1; side <= 1; side += 2) {
                const int qx = x + side * k * dx, qy = y + side * k * dy;
                if (qy < 0 || qy >= f.height) continue;
                const long j = long(qy) * w + qx;
                f8 pq[3], nq[3], s[3];
                deinterleave3(f.position + 3 * j, pq[0], pq[1], pq[2]);
                deinterleave3(f.normal + 3 * j, nq[0], nq[1], nq[2]);
                deinterleave3(src + 3 * j, s[0], s[1], s[2]);
                f8 wt = g[k] * edgeWeight8(nc, pc, nq, pq, f.edges);
                wt = wt > 0.0f ? wt : 0.0f;
                for (int c = 0; c < 3; ++c) sum[c] = sum[c] + wt * s[c];
                total = total + wt;
            }
        interleave3(sum[0] / total, sum[1] / total, sum[2] / total, dst + 3 * i);
        x += 8;
    }
}

} // namespace

void maraPackTaps(const MaraFrame& f, const float* src, bool guide, float* taps, long y0, long y1) {
    for (long y = y0; y < y1; ++y) packRow(f, src, guide, taps, int(y));
}

void maraSparseTile(const MaraFrame& f, const float* taps, bool final, int x0, int x1, long y0,
                    long y1, const MaraTapTables* tables) {
    for (long y = y0; y < y1; ++y) sparseRow(f, taps, final, int(y), x0, x1, tables);
}

void MaraTapTables::build(const MaraFrame& f) {
    // As maraDisocclusionRadius gives them for a box min of h (or 1, normalised) and of 0.
    const float confident = f.normaliseConfidence ? 0.0f : (1.0f - f.h) * float(f.maxRadius);
    const float candidates[kRadii] = {confident, float(f.maxRadius), confident * f.radiusBoost,
                                      float(f.maxRadius) * f.radiusBoost};
    for (int t = 0; t < kRadii; ++t) {
        radius[t] = candidates[t];
        maraTapTable(f.finalSpiral, f.finalTaps * kMaraSpiralRotations, radius[t],
                     f.finalSigma * radius[t], offsets[t], gauss[t]);
    }
}

void maraMedianRows(const MaraFrame& f, long y0, long y1) {
    for (long y = y0; y < y1; ++y) medianRow(f, int(y));
}

void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, int dx,
                    int dy) {
    for (long y = y0; y < y1; ++y) glossyRow(f, src, dst, int(y), dx, dy);
}

} // namespace bmfr::cpu
