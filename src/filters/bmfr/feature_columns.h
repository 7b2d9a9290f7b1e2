// Evaluation and per-block scaling of BMFR feature columns.
#pragma once
#include "core/vec.h"
#include <algorithm>
#include <bmfr/features.h>
#include <cmath>
#include <vector>

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

/// One block's gathered sources, structure-of-arrays: W values each.
struct BlockSources {
    const float* normal[3];
    const float* position[3];
    const float* extras; ///< extra buffer e starts at extras + e * W
};

/// Fills the M unscaled feature columns (W values each, column f at out + f * W) from the
/// block's sources. The switch runs once per column, not per pixel.
inline void buildFeatureColumns(const std::vector<Feature>& features, const BlockSources& src,
                                int W, float* out) {
    for (size_t f = 0; f < features.size(); ++f) {
        const Feature& feat = features[f];
        float* col = out + long(f) * W;
        const float* from = nullptr;
        switch (feat.source) {
        case FeatureSource::One:
            std::fill(col, col + W, 1.0f);
            continue;
        case FeatureSource::NormalX:
            from = src.normal[0];
            break;
        case FeatureSource::NormalY:
            from = src.normal[1];
            break;
        case FeatureSource::NormalZ:
            from = src.normal[2];
            break;
        case FeatureSource::PositionX:
            from = src.position[0];
            break;
        case FeatureSource::PositionY:
            from = src.position[1];
            break;
        case FeatureSource::PositionZ:
            from = src.position[2];
            break;
        case FeatureSource::Extra:
            from = src.extras + size_t(feat.extraIndex) * size_t(W);
            break;
        }
        if (feat.exponent == 1.0f)
            std::copy(from, from + W, col);
        else if (feat.exponent == 2.0f)
            for (int k = 0; k < W; ++k) col[k] = from[k] * from[k];
        else
            for (int k = 0; k < W; ++k) col[k] = applyExponent(from[k], feat.exponent);
    }
}

} // namespace bmfr
