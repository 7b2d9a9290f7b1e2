// Evaluation and per-block scaling of BMFR feature columns.
#pragma once
#include "core/vec.h"
#include <bmfr/features.h>
#include <cmath>

namespace bmfr {

/// v^e for e other than 1 and 2. Non-integer powers of negative values are undefined: the sign
/// is kept (odd extension).
inline float applyExponent(float v, float e) {
    float a = std::pow(std::fabs(v), e);
    return v < 0 ? -a : a;
}

/// The authors' block scaling: (v-min)/(max-min) when the range exceeds 1, else v-min.
BMFR_HD float scaleFeature(float v, float lo, float hi) {
    float range = hi - lo;
    return range > 1.0f ? (v - lo) / range : v - lo;
}

} // namespace bmfr
