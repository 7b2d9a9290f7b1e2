// remodulate (temporal/modulation.h) for eight pixels, with the same roundings.
#pragma once
#include "backend/cpu/simd.h"
#include "temporal/pixel_input.h"

namespace bmfr::cpu {

/// c of pixels [i, i + n) times the guarded albedo when `remodulateAlbedo`, plus the finite
/// emission when the frame has one.
BMFR_SIMD_INLINE void remodulate8(simd::f8 c[3], const InputPlanes& in, long i, int n,
                                  bool remodulateAlbedo, float albedoEpsilon) {
    using namespace simd;
    if (remodulateAlbedo) {
        f8 albedo[3];
        loadXyz8(in.albedo + 3 * i, n, albedo);
        const f8 eps = splat8(albedoEpsilon);
        for (int ch = 0; ch < 3; ++ch) {
            const f8 v = albedo[ch];
            c[ch] = c[ch] * ((v - v) == 0.0f && v > eps ? v : eps); // guardAlbedo
        }
    }
    if (in.emission) {
        f8 e[3];
        loadXyz8(in.emission + 3 * i, n, e);
        const i8 finite =
            ((e[0] - e[0]) == 0.0f) & ((e[1] - e[1]) == 0.0f) & ((e[2] - e[2]) == 0.0f);
        for (int ch = 0; ch < 3; ++ch) c[ch] = finite ? c[ch] + e[ch] : c[ch];
    }
}

} // namespace bmfr::cpu
