// Evaluation and per-block scaling of BMFR feature columns.
#pragma once
#include "core/vec.h"
#include <bmfr/features.h>
#include <cmath>

namespace bmfr {

/// Raw value of a feature (before block scaling) from a pixel's normal, position and extras.
inline float featureValue(const Feature& f, Vec3 n, Vec3 p, const float* extras) {
    float v;
    switch (f.source) {
    case FeatureSource::One:
        return 1.0f;
    case FeatureSource::NormalX:
        v = n.x;
        break;
    case FeatureSource::NormalY:
        v = n.y;
        break;
    case FeatureSource::NormalZ:
        v = n.z;
        break;
    case FeatureSource::PositionX:
        v = p.x;
        break;
    case FeatureSource::PositionY:
        v = p.y;
        break;
    case FeatureSource::PositionZ:
        v = p.z;
        break;
    default:
        v = extras[f.extraIndex];
        break;
    }
    if (f.exponent == 1.0f) return v;
    if (f.exponent == 2.0f) return v * v;
    // Non-integer powers of negative values are undefined: keep the sign (odd extension).
    float a = std::pow(std::fabs(v), f.exponent);
    return v < 0 ? -a : a;
}

/// The authors' block scaling: (v-min)/(max-min) when the range exceeds 1, else v-min.
BMFR_HD float scaleFeature(float v, float lo, float hi) {
    float range = hi - lo;
    return range > 1.0f ? (v - lo) / range : v - lo;
}

} // namespace bmfr
