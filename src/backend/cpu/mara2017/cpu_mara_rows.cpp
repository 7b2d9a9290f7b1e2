#include "backend/cpu/mara2017/cpu_mara_rows.h"
#include "backend/cpu/simd.h"
#include <cstring>
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#define BMFR_MARA_HW_GATHER 1
#else
#define BMFR_MARA_HW_GATHER 0
#endif

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

// The sparse rows twice: AVX2 (chosen at run time, once, so the bits repeat on one machine)
// and the baseline.
namespace lanes {
#define BMFR_MARA_GATHER_AVX2 0
#include "backend/cpu/mara2017/cpu_mara_sparse_row.inc"
#undef BMFR_MARA_GATHER_AVX2
} // namespace lanes
#if BMFR_MARA_HW_GATHER
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
namespace avx2 {
#define BMFR_MARA_GATHER_AVX2 1
#include "backend/cpu/mara2017/cpu_mara_sparse_row.inc"
#undef BMFR_MARA_GATHER_AVX2
} // namespace avx2
#pragma GCC pop_options
#endif

void sparseRow(const MaraFrame& f, const float* src, bool final, int y) {
#if BMFR_MARA_HW_GATHER
    static const bool hasAvx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    if (hasAvx2) return avx2::sparseRow(f, src, final, y);
#endif
    lanes::sparseRow(f, src, final, y);
}

BMFR_SIMD_CLONES void medianRow(const MaraFrame& f, int y) {
    const int w = f.width;
    int rows[3];
    for (int d = -1; d <= 1; ++d) rows[d + 1] = y + d < 0 ? 0 : y + d >= f.height ? f.height - 1 : y + d;
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

BMFR_SIMD_CLONES void glossyRow(const MaraFrame& f, const float* src, float* dst, int y, int dx,
                                int dy) {
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

void maraSparseRows(const MaraFrame& f, const float* src, bool final, long y0, long y1) {
    for (long y = y0; y < y1; ++y) sparseRow(f, src, final, int(y));
}

void maraMedianRows(const MaraFrame& f, long y0, long y1) {
    for (long y = y0; y < y1; ++y) medianRow(f, int(y));
}

void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, int dx,
                    int dy) {
    for (long y = y0; y < y1; ++y) glossyRow(f, src, dst, int(y), dx, dy);
}

} // namespace bmfr::cpu
