// WALR's edge-aware a-trous averages (paper section 3.2) and the per-pixel regression on them.
// Each pixel carries 14 running averages of its products of features (1, u, v) and colour; each
// iteration t averages a 3x3 of taps at spacing 3^t, so after T iterations every pixel of the
// 3^T x 3^T window has been averaged exactly once. BMFR_HD over planes of one channel each.
#pragma once
#include "core/half.h"
#include "filters/walr/cholesky3.h"
#include "filters/walr/edge_tracing.h"

namespace bmfr {

/// Averages per pixel, as planes in this order: XX01 XX02 XX11 XX12 XX22 (XX00 = 1 is not
/// stored), then for each colour channel c: YX_c0 (the mean colour) YX_c1 YX_c2.
constexpr int kWalrAverages = 14;

/// The averages of one sample: colour y with features (1, f.x, f.y).
BMFR_HD void walrSampleProducts(Vec3 y, Vec2 f, float a[kWalrAverages]) {
    a[0] = f.x, a[1] = f.y, a[2] = f.x * f.x, a[3] = f.x * f.y, a[4] = f.y * f.y;
    for (int c = 0; c < 3; ++c) {
        a[5 + 3 * c] = y[c];
        a[6 + 3 * c] = y[c] * f.x;
        a[7 + 3 * c] = y[c] * f.y;
    }
}

/// Where channel k of pixel i lies: at k * channelStride + i * pixelStride (planes, or
/// interleaved pixels).
struct AverageLayout {
    long channelStride = 0, pixelStride = 1;
    BMFR_HD long at(int k, long i) const { return k * channelStride + i * pixelStride; }
};

/// One iteration's averages, in and out. `weightIn` and `weightOut` are the sample-count
/// weights W (null when they are dropped, as in the paper).
struct WalrLevel {
    const float* in = nullptr;
    float* out = nullptr;
    const float* weightIn = nullptr;
    float* weightOut = nullptr;
    AverageLayout layout;
    int iteration = 0; ///< t: taps at spacing 3^t
    int step = 1;
    /// Half averages (WalrSettings::halfAverages): the output rounded through half
    /// (roundToHalf), and on the CPU backend input and output stored as 16 halves per pixel.
    bool halfIn = false, halfOut = false;
    uint32_t frame = 0, seed = 0;
    /// Stepped tracing's state (EdgeGuide::stepped), in the reference backend's
    /// layout; the CPU backend keeps its own.
    SteppedTrace trace;
};

/// The 8 tap directions in the order every backend sums them.
BMFR_HD int walrTapX(int tap) {
    return (tap < 4 ? tap : tap + 1) % 3 - 1;
}
BMFR_HD int walrTapY(int tap) {
    return (tap < 4 ? tap : tap + 1) / 3 - 1;
}

/// One iteration at pixel (x, y): the centre with weight 1 (times its W), then the 8 traced taps.
BMFR_HD void walrAtrousPixel(const EdgeGuide& g, const WalrLevel& l, int x, int y) {
    const long i = long(y) * g.width + x;
    const EdgeCentre c = edgeCentre(g, i);
    float sum[kWalrAverages];
    float total = l.weightIn ? l.weightIn[i] : 1.0f;
    for (int k = 0; k < kWalrAverages; ++k) sum[k] = total * l.in[l.layout.at(k, i)];
    for (int tap = 0; tap < 8; ++tap) {
        const int ux = walrTapX(tap), uy = walrTapY(tap);
        const uint32_t hash = replacementHash(i, l.frame, l.iteration, tap, l.seed);
        const TracedTap t = g.stepped() ? traceTapStepped(g, c, l.trace, i, tap, x, y, ux, uy,
                                                          l.iteration, l.step, hash)
                                        : traceTap(g, c, x, y, ux, uy, l.step, hash);
        if (!(t.weight > 0)) continue;
        const long j = long(y + t.steps * uy) * g.width + x + t.steps * ux;
        const float w = l.weightIn ? t.weight * l.weightIn[j] : t.weight;
        for (int k = 0; k < kWalrAverages; ++k) sum[k] += w * l.in[l.layout.at(k, j)];
        total += w;
    }
    for (int k = 0; k < kWalrAverages; ++k) {
        const float v = sum[k] / total;
        l.out[l.layout.at(k, i)] = l.halfOut ? roundToHalf(v) : v;
    }
    if (l.weightOut) l.weightOut[i] = total;
}

/// The regression's value at a pixel with features f, from its final averages a: solve, then
/// beta . (1, f); clamped to >= 0 (an extrapolated fit can go negative), 0 if not finite.
template <class T> BMFR_HD Vec3 walrPredict(const T a[kWalrAverages], Vec2 f, T eps) {
    const Cholesky3<T> c = choleskyClamped<T>(a[0], a[1], a[2], a[3], a[4], eps);
    float out[3];
    for (int ch = 0; ch < 3; ++ch) {
        const T rhs[3] = {a[5 + 3 * ch], a[6 + 3 * ch], a[7 + 3 * ch]};
        T beta[3];
        choleskySolve(c, rhs, beta);
        const T v = beta[0] + beta[1] * T(f.x) + beta[2] * T(f.y);
        out[ch] = v > 0 ? float(v) : 0.0f; // NaN fails v > 0
    }
    return {out[0], out[1], out[2]};
}

/// walrPredict of pixel i from the last iteration's averages.
BMFR_HD Vec3 walrSolvePixel(const float* averages, const AverageLayout& layout, long i, Vec2 f,
                            float eps) {
    float a[kWalrAverages];
    for (int k = 0; k < kWalrAverages; ++k) a[k] = averages[layout.at(k, i)];
    return walrPredict<float>(a, f, eps);
}

} // namespace bmfr
