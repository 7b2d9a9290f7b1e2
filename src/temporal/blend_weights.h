// Blend weights of BMFR's two temporal accumulations: cumulative average first, then EMA.
#pragma once
#include "core/host_device.h"
#include <cmath>
#include <cstdint>

namespace bmfr {

/// Phase I: weight of the new sample given the reprojected history length n (samples).
BMFR_HD float firstBlendWeight(float historySamples, float minAlpha) {
    const float w = 1.0f / (historySamples + 1.0f);
    return w > minAlpha ? w : minAlpha;
}

/// Phase I: new history length, stored in 8 bits: round(n) + 1, saturating at 255.
BMFR_HD uint8_t nextHistoryLength(float historySamples) {
    if (historySamples > 254.0f) return 255;
    // Round half to even as the authors' convert_uchar_sat_rte; lrintf uses the default mode.
    return uint8_t(std::lrintf(historySamples) + 1);
}

/// Phase III: weight of the new fitted frame given the phase I history length (which already
/// counts the new frame).
BMFR_HD float secondBlendWeight(uint8_t historyLength, float minAlpha) {
    const float w = 1.0f / float(historyLength > 0 ? historyLength : 1);
    return w > minAlpha ? w : minAlpha;
}

} // namespace bmfr
