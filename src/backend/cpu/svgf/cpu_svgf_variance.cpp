#include "backend/cpu/svgf/cpu_svgf_variance.h"
#include "backend/cpu/simd.h"
#include "backend/cpu/svgf/cpu_svgf_weights.h"
#include <algorithm>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// svgfDepthGradient of n <= 8 pixels from column x of row y: eight wide away from the image's
/// sides, pixel by pixel at them.
BMFR_SIMD_INLINE void depthGradient8(const SvgfFrame& f, long y, int x, int n, f8& gx, f8& gy) {
    const int w = f.width;
    const float* z = f.depth + y * w + x;
    if (x >= 1 && x + 9 <= w && y >= 1 && y + 1 < f.height) {
        gx = (load8(z + 1) - load8(z - 1)) / 2.0f;
        gy = (load8(z + w) - load8(z - w)) / 2.0f;
        return;
    }
    gx = gy = f8{};
    for (int l = 0; l < n; ++l) {
        const Vec2 g = svgfDepthGradient(f, x + l, int(y));
        gx[l] = g.x, gy[l] = g.y;
    }
}

/// The 7x7 estimate's moments of eight pixels from column x of row y (pixel i), from the first
/// level's planes (their normal is 0 and mask 0 without a sample, and in the aprons either
/// side of a row, so that a tap past a side weighs 0); gx and gy are their depth gradient.
/// `inside`: every tap inside the row, whose moments are then read as vectors.
template <int kExponent>
BMFR_SIMD_INLINE void bilateralMoments(const SvgfFrame& f, const SvgfSettings& s,
                                       const SvgfFirstLevel& level, long y, int x, long i, f8 gx,
                                       f8 gy, bool inside, f8& m1, f8& m2) {
    const int w = f.width;
    const long p = y * level.pitch + x;
    const f8 n0[3] = {load8(level.nx + p), load8(level.ny + p), load8(level.nz + p)};
    const f8 z0 = load8(level.depth + p), l0 = load8(level.colour[4] + p);
    f8 sw{}, s1{}, s2{};
    for (int dy = -3; dy <= 3; ++dy) {
        if (y + dy < 0 || y + dy >= f.height) continue;
        // A row's seven taps: their weights (one power of two each for the default exponent, as
        // the a-trous levels' taps), then their sums.
        f8 wq[7], mq1[7], mq2[7];
        i8 facing[7]; // n0 . nq > 0: the reference's normal weight is 0 elsewhere
        for (int dx = -3; dx <= 3; ++dx) {
            const int t = dx + 3;
            const long q = p + dy * level.pitch + dx;
            const f8 nq[3] = {load8(level.nx + q), load8(level.ny + q), load8(level.nz + q)};
            const long j = i + long(dy) * w + dx;
            if (inside) {
                loadXy8(f.moments + 2 * j, 8, mq1[t], mq2[t]);
            } else { // lane by lane, the taps past a side (weight 0) as 0
                mq1[t] = mq2[t] = f8{};
                for (int l = 0; l < 8; ++l)
                    if (x + l + dx >= 0 && x + l + dx < w)
                        mq1[t][l] = f.moments[2 * (j + l)], mq2[t][l] = f.moments[2 * (j + l) + 1];
            }
            const f8 slope = abs8(gx * float(dx) + gy * float(dy));
            const f8 depthArg = abs8(z0 - load8(level.depth + q)) / (s.phiDepth * slope + 1e-6f);
            const f8 lq = load8(level.colour[4] + q);
            if constexpr (kExponent == 128) {
                const f8 lumArg = abs8(l0 - lq) * 0.1f;
                const f8 away = 1.0f - ((n0[0] * nq[0] + n0[1] * nq[1]) + n0[2] * nq[2]);
                wq[t] = (depthArg + lumArg) * -kLog2E + normalLog2Power128(away);
                facing[t] = away < 1.0f;
            } else {
                const f8 lumArg = abs8(l0 - lq) / 10.0f;
                const f8 dotN = (n0[0] * nq[0] + n0[1] * nq[1]) + n0[2] * nq[2];
                wq[t] = normalPower<kExponent>(dotN, int(s.phiNormal)) *
                        expNonPositive8(-(depthArg + lumArg));
                facing[t] = ~i8{};
            }
        }
        if constexpr (kExponent == 128) exp2NonPositiveRows(wq, 7, -1);
        for (int dx = -3; dx <= 3; ++dx) {
            const int t = dx + 3;
            // A tap without a sample, or facing away, adds exactly nothing, as in the reference
            // (exp2NonPositiveRows' floor, 2^-126, would otherwise make a centre whose normal is
            // 0 the plain mean of its window, where the reference keeps its own moments).
            const i8 sampled = load8(level.mask + p + dy * level.pitch + dx) > 0.0f;
            const f8 weight = sampled & facing[t] ? wq[t] : f8{};
            sw += weight;
            s1 += weight * mq1[t];
            s2 += weight * mq2[t];
        }
    }
    const i8 some = sw > 0.0f;
    m1 = some ? s1 / sw : m1;
    m2 = some ? s2 / sw : m2;
}

/// Whether eight pixels from column x of a row w wide have every 7x7 tap inside the row.
inline bool tapsInside(int x, int w) {
    return x >= 3 && x + 8 + 3 <= w;
}

/// The first level but its variance, over rows [y0, y1): the guides, the colour and its
/// luminance.
BMFR_SIMD_DISPATCH(void, firstLevelRows,
                   (const SvgfFrame& f, const SvgfFirstLevel& level, long y0, long y1),
                   (f, level, y0, y1)) {
    const int w = f.width;
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < w; x += 8) {
            const int n = std::min(8, w - x);
            const long i = y * w + x, p = y * level.pitch + x;
            f8 gx, gy;
            depthGradient8(f, y, x, n, gx, gy);
            const i8 sampled = loadBytes(f.length + i, n) != 0;
            f8 normal[3], c[3];
            loadXyz8(f.normal + 3 * i, n, normal);
            storeFirst(level.nx + p, sampled ? normal[0] : f8{}, n);
            storeFirst(level.ny + p, sampled ? normal[1] : f8{}, n);
            storeFirst(level.nz + p, sampled ? normal[2] : f8{}, n);
            storeFirst(level.depth + p, loadFirst(f.depth + i, n), n);
            storeFirst(level.gradX + p, gx, n);
            storeFirst(level.gradY + p, gy, n);
            storeFirst(level.mask + p, sampled ? splat8(1.0f) : f8{}, n);
            loadXyz8(f.integrated + 3 * i, n, c);
            for (int k = 0; k < 3; ++k) storeFirst(level.colour[k] + p, c[k], n);
            storeFirst(level.colour[4] + p, luminance8(c), n);
        }
}

template <int kExponent>
BMFR_SIMD_INLINE void varianceRowsOf(const SvgfFrame& f, const SvgfSettings& s,
                                     const SvgfFirstLevel& level, long y0, long y1,
                                     float* varianceOut) {
    const int w = f.width;
    const f8 limit = splat8(float(s.spatialVarianceFrames));
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < w; x += 8) {
            const int n = std::min(8, w - x);
            const long i = y * w + x, p = y * level.pitch + x;
            const f8 length = __builtin_convertvector(loadBytes(f.length + i, n), f8);
            const i8 estimate = (length > 0.0f) & (length < limit);
            f8 variance{};
            f8 m1, m2;
            loadXy8(f.moments + 2 * i, n, m1, m2);
            variance = m2 - m1 * m1;
            if (anyLane(estimate)) {
                f8 e1 = m1, e2 = m2;
                bilateralMoments<kExponent>(f, s, level, y, x, i, load8(level.gradX + p),
                                            load8(level.gradY + p), tapsInside(x, w), e1, e2);
                // Boost the uncertain estimate of short histories (as the authors' code).
                const f8 boosted = (e2 - e1 * e1) * 4.0f / (estimate ? length : splat8(1.0f));
                variance = estimate ? boosted : variance;
            }
            variance = variance > 0.0f ? variance : f8{}; // std::fmax(variance, 0)
            storeFirst(varianceOut + i, variance, n);
            storeFirst(level.colour[3] + p, variance, n);
        }
}

BMFR_SIMD_DISPATCH(void, varianceRows,
                   (const SvgfFrame& f, const SvgfSettings& s, const SvgfFirstLevel& level, long y0,
                    long y1, float* variance),
                   (f, s, level, y0, y1, variance)) {
    if (s.phiNormal == 128.0f)
        varianceRowsOf<128>(f, s, level, y0, y1, variance);
    else
        varianceRowsOf<0>(f, s, level, y0, y1, variance);
}

} // namespace

void svgfFirstLevelRows(const SvgfFrame& f, const SvgfFirstLevel& level, long y0, long y1) {
    firstLevelRows(f, level, y0, y1);
}

void svgfVarianceRows(const SvgfFrame& f, const SvgfSettings& s, const SvgfFirstLevel& level,
                      long y0, long y1, float* variance) {
    varianceRows(f, s, level, y0, y1, variance);
}

} // namespace bmfr::cpu
