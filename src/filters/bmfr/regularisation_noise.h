// BMFR's stochastic regularisation (paper section 4.2): uniform noise of the given amplitude
// added to each non-constant feature column, the same for every block of a frame and new each
// frame. One BMFR_HD definition, so host and device draw the same bits.
#pragma once
#include "core/hash.h"
#include <cstdint>

namespace bmfr {

/// The noise of feature `f` at block pixel `k` of frame `frame`: amplitude * U(-1, 1), or 0
/// for the constant feature.
BMFR_HD float regularisationNoise(uint32_t seed, uint32_t frame, int f, int k, float amplitude,
                                  bool constantFeature) {
    if (constantFeature) return 0.0f;
    const float u = unitFloat(hashKeys(seed, frame, uint32_t(f), uint32_t(k)));
    return amplitude * (2.0f * u - 1.0f);
}

} // namespace bmfr
