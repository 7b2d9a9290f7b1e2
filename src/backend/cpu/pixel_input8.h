// readPixel (temporal/pixel_input.h) and the blend weights (temporal/blend_weights.h) for eight
// pixels at once, with the same roundings, counts and decisions: shared by BMFR's phase I and
// SVGF's accumulation.
#pragma once
#include "backend/cpu/simd.h"
#include "temporal/pixel_input.h"

namespace bmfr::cpu {

/// The eight pixels' inputs as readPixel reads them.
struct Inputs8 {
    simd::f8 position[3], normal[3], color[3];
};

/// readPixel of the n <= 8 pixels [i, i + n): NaN and Inf replaced by 0 and counted in `bad`
/// (extras included), the emission taken out, the colour demodulated as `modes` says.
BMFR_SIMD_INLINE Inputs8 readInputs8(const InputPlanes& in, const InputModes& modes, long i, int n,
                                     int64_t& bad) {
    using namespace simd;
    Inputs8 px;
    f8 albedo[3], e[3] = {};
    loadXyz8(in.normal + 3 * i, n, px.normal);
    loadXyz8(in.position + 3 * i, n, px.position);
    loadXyz8(in.albedo + 3 * i, n, albedo);
    loadXyz8(in.color + 3 * i, n, px.color);
    if (in.emission) loadXyz8(in.emission + 3 * i, n, e);
    // One test for all channels, on their sum: a NaN or an infinity in any makes the sum
    // non-finite. So can an overflow of finite values, which only sends the group through the
    // exact per-channel test.
    f8 sum = (e[0] + e[1]) + e[2];
    for (int c = 0; c < 3; ++c) sum += (px.normal[c] + px.position[c]) + (albedo[c] + px.color[c]);
    if (__builtin_expect(!allLanes(finite8(sum)), 0)) {
        finiteOrZero8(px.normal, bad), finiteOrZero8(px.position, bad);
        finiteOrZero8(albedo, bad), finiteOrZero8(px.color, bad), finiteOrZero8(e, bad);
    }
    const f8 eps = splat8(modes.albedoEpsilon);
    f8 g[3];
    for (int c = 0; c < 3; ++c) g[c] = albedo[c] > eps ? albedo[c] : eps;
    if (in.emission) {
        for (int c = 0; c < 3; ++c) {
            if (modes.colorIsDemodulated) e[c] = e[c] / g[c];
            px.color[c] = max8(px.color[c] - e[c], f8{});
        }
    }
    for (int k = 0; k < in.extraCount; ++k) {
        const f8 v = loadFirst(in.extras[k] + i, n);
        bad += countLanes(~finite8(v));
    }
    if (modes.demodulate && !modes.colorIsDemodulated)
        for (int c = 0; c < 3; ++c) px.color[c] = px.color[c] / g[c];
    return px;
}

/// firstBlendWeight for eight lanes.
BMFR_SIMD_INLINE simd::f8 firstBlendWeight8(simd::f8 samples, float minAlpha) {
    const simd::f8 w = 1.0f / (samples + 1.0f);
    return w > minAlpha ? w : simd::splat8(minAlpha);
}
/// lrintf of 0 <= v < 2^22 in the default rounding mode (half to even), through 1.5 x 2^23.
BMFR_SIMD_INLINE simd::f8 roundHalfEven8(simd::f8 v) {
    return (v + 12582912.0f) - 12582912.0f;
}
/// nextHistoryLength for eight lanes (larger values saturate below).
BMFR_SIMD_INLINE simd::f8 nextHistoryLength8(simd::f8 samples) {
    return samples > 254.0f ? simd::splat8(255.0f) : roundHalfEven8(samples) + 1.0f;
}

} // namespace bmfr::cpu
