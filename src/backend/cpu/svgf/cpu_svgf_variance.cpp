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

/// The 7x7 estimate's moments of eight pixels from i, every tap inside the row; gx and gy are
/// their depth gradient.
template <int kExponent>
BMFR_SIMD_INLINE void bilateralMoments(const SvgfFrame& f, const SvgfSettings& s, int y, long i,
                                       const f8 centre[3], f8 gx, f8 gy, f8& m1, f8& m2) {
    const int w = f.width;
    f8 n0[3];
    deinterleave3(f.normal + 3 * i, n0[0], n0[1], n0[2]);
    const f8 z0 = load8(f.depth + i), l0 = luminance8(centre);
    f8 sw{}, s1{}, s2{};
    for (int dy = -3; dy <= 3; ++dy) {
        if (y + dy < 0 || y + dy >= f.height) continue;
        // A row's seven taps: their weights (one power of two each for the default exponent, as
        // the a-trous levels' taps), then their sums.
        f8 wq[7], mq1[7], mq2[7];
        i8 facing[7]; // n0 . nq > 0: the reference's normal weight is 0 elsewhere
        for (int dx = -3; dx <= 3; ++dx) {
            const int t = dx + 3;
            const long q = i + long(dy) * w + dx;
            f8 nq[3], cq[3];
            deinterleave3(f.normal + 3 * q, nq[0], nq[1], nq[2]);
            deinterleave3(f.integrated + 3 * q, cq[0], cq[1], cq[2]);
            loadXy8(f.moments + 2 * q, 8, mq1[t], mq2[t]);
            const f8 slope = abs8(gx * float(dx) + gy * float(dy));
            const f8 depthArg = abs8(z0 - load8(f.depth + q)) / (s.phiDepth * slope + 1e-6f);
            if constexpr (kExponent == 128) {
                const f8 lumArg = abs8(l0 - luminance8(cq)) * 0.1f;
                const f8 away = 1.0f - ((n0[0] * nq[0] + n0[1] * nq[1]) + n0[2] * nq[2]);
                wq[t] = (depthArg + lumArg) * -kLog2E + normalLog2Power128(away);
                facing[t] = away < 1.0f;
            } else {
                const f8 lumArg = abs8(l0 - luminance8(cq)) / 10.0f;
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
            const i8 sampled = loadBytes(f.length + i + long(dy) * w + dx, 8) != 0;
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

/// The guides and the result of n <= 8 pixels from i (column x of row y) into the first level.
BMFR_SIMD_INLINE void storeFirstLevel(const SvgfFrame& f, const SvgfFirstLevel& level, long i,
                                      long y, int x, int n, const f8 c[3], f8 variance, f8 gx,
                                      f8 gy) {
    const long p = y * level.pitch + x;
    const i8 sampled = loadBytes(f.length + i, n) != 0;
    f8 normal[3];
    loadXyz8(f.normal + 3 * i, n, normal);
    storeFirst(level.nx + p, sampled ? normal[0] : f8{}, n);
    storeFirst(level.ny + p, sampled ? normal[1] : f8{}, n);
    storeFirst(level.nz + p, sampled ? normal[2] : f8{}, n);
    storeFirst(level.depth + p, loadFirst(f.depth + i, n), n);
    storeFirst(level.gradX + p, gx, n);
    storeFirst(level.gradY + p, gy, n);
    storeFirst(level.mask + p, sampled ? splat8(1.0f) : f8{}, n);
    for (int k = 0; k < 3; ++k) storeFirst(level.colour[k] + p, c[k], n);
    storeFirst(level.colour[3] + p, variance, n);
    storeFirst(level.colour[4] + p, luminance8(c), n);
}

template <int kExponent>
BMFR_SIMD_INLINE void varianceRowsOf(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1,
                                     float* filtered, float* varianceOut,
                                     const SvgfFirstLevel* level) {
    const int w = f.width;
    const f8 limit = splat8(float(s.spatialVarianceFrames));
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < w; x += 8) {
            const int n = std::min(8, w - x);
            const long i = y * w + x;
            const f8 length = __builtin_convertvector(loadBytes(f.length + i, n), f8);
            const i8 estimate = (length > 0.0f) & (length < limit);
            const bool inside = x >= 3 && x + 8 + 3 <= w;
            // With the level planes the gradient is made here (svgfAccumulate left it).
            f8 gx, gy;
            if (level)
                depthGradient8(f, y, x, n, gx, gy);
            else
                loadXy8(f.depthGradient + 2 * i, n, gx, gy);
            if (anyLane(estimate) && !inside) { // taps past a side: the reference's pixels
                if (level) storeXy8(f.depthGradient + 2 * i, n, gx, gy); // which they read
                for (int l = 0; l < n; ++l)
                    svgfVariancePixel(f, s, x + l, int(y), filtered, varianceOut);
                if (level) {
                    f8 c[3] = {}, variance{};
                    for (int l = 0; l < n; ++l) {
                        for (int k = 0; k < 3; ++k) c[k][l] = filtered[4 * (i + l) + k];
                        variance[l] = filtered[4 * (i + l) + 3];
                    }
                    storeFirstLevel(f, *level, i, y, x, n, c, variance, gx, gy);
                }
                continue;
            }
            f8 c[3], m1, m2;
            loadXyz8(f.integrated + 3 * i, n, c);
            loadXy8(f.moments + 2 * i, n, m1, m2);
            f8 variance = m2 - m1 * m1;
            if (anyLane(estimate)) {
                f8 e1 = m1, e2 = m2;
                bilateralMoments<kExponent>(f, s, int(y), i, c, gx, gy, e1, e2);
                // Boost the uncertain estimate of short histories (as the authors' code).
                const f8 boosted = (e2 - e1 * e1) * 4.0f / (estimate ? length : splat8(1.0f));
                variance = estimate ? boosted : variance;
            }
            variance = variance > 0.0f ? variance : f8{}; // std::fmax(variance, 0)
            storeFirst(varianceOut + i, variance, n);
            if (level) {
                storeFirstLevel(f, *level, i, y, x, n, c, variance, gx, gy);
                continue;
            }
            float out[32];
            for (int l = 0; l < 8; ++l) {
                out[4 * l] = c[0][l], out[4 * l + 1] = c[1][l], out[4 * l + 2] = c[2][l];
                out[4 * l + 3] = variance[l];
            }
            std::memcpy(filtered + 4 * i, out, sizeof(float) * 4 * size_t(n));
        }
}

BMFR_SIMD_DISPATCH(void, varianceRows,
                   (const SvgfFrame& f, const SvgfSettings& s, long y0, long y1, float* filtered,
                    float* variance, const SvgfFirstLevel* level),
                   (f, s, y0, y1, filtered, variance, level)) {
    if (s.phiNormal == 128.0f)
        varianceRowsOf<128>(f, s, y0, y1, filtered, variance, level);
    else
        varianceRowsOf<0>(f, s, y0, y1, filtered, variance, level);
}

} // namespace

void svgfVarianceRows(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1, float* filtered,
                      float* variance, const SvgfFirstLevel* level) {
    varianceRows(f, s, y0, y1, filtered, variance, level);
}

} // namespace bmfr::cpu
