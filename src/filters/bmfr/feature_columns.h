// Evaluation and per-block scaling of BMFR feature columns (paper eq. 8 and the authors' block
// scaling).
#pragma once
#include "core/vec.h"
#include <bmfr/features.h>

namespace bmfr {

/// v^e for e other than 1 and 2. Non-integer powers of negative values are undefined: the sign
/// is kept (odd extension).
BMFR_HD float applyExponent(float v, float e) {
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
BMFR_HD void buildFeatureColumns(const Feature* features, int M, const BlockSources& src, int W,
                                 float* out) {
    for (int f = 0; f < M; ++f) {
        const Feature& feat = features[f];
        float* col = out + long(f) * W;
        const float* from = nullptr;
        switch (feat.source) {
        case FeatureSource::One:
            for (int k = 0; k < W; ++k) col[k] = 1.0f;
            continue;
        case FeatureSource::NormalX:
        case FeatureSource::NormalY:
        case FeatureSource::NormalZ:
            from = src.normal[int(feat.source) - int(FeatureSource::NormalX)];
            break;
        case FeatureSource::PositionX:
        case FeatureSource::PositionY:
        case FeatureSource::PositionZ:
            from = src.position[int(feat.source) - int(FeatureSource::PositionX)];
            break;
        case FeatureSource::Extra:
            from = src.extras + long(feat.extraIndex) * W;
            break;
        }
        if (feat.exponent == 1.0f)
            for (int k = 0; k < W; ++k) col[k] = from[k];
        else if (feat.exponent == 2.0f)
            for (int k = 0; k < W; ++k) col[k] = from[k] * from[k];
        else
            for (int k = 0; k < W; ++k) col[k] = applyExponent(from[k], feat.exponent);
    }
}

/// A feature's source value raised to its exponent, as buildFeatureColumns does.
BMFR_HD float raiseFeature(float v, float exponent) {
    if (exponent == 1.0f) return v;
    if (exponent == 2.0f) return v * v;
    return applyExponent(v, exponent);
}

/// Feature `feat`'s unscaled value at one pixel from its sources (normal, position, and the
/// pixel's extras, one value each): buildFeatureColumns for a single row, for backends that
/// fit a block row by row.
BMFR_HD float featureValue(const Feature& feat, const float normal[3], const float position[3],
                           const float* extras) {
    float v = 1.0f;
    switch (feat.source) {
    case FeatureSource::One:
        return 1.0f;
    case FeatureSource::NormalX:
    case FeatureSource::NormalY:
    case FeatureSource::NormalZ:
        v = normal[int(feat.source) - int(FeatureSource::NormalX)];
        break;
    case FeatureSource::PositionX:
    case FeatureSource::PositionY:
    case FeatureSource::PositionZ:
        v = position[int(feat.source) - int(FeatureSource::PositionX)];
        break;
    case FeatureSource::Extra:
        v = extras[feat.extraIndex];
        break;
    }
    return raiseFeature(v, feat.exponent);
}

} // namespace bmfr
