// Colour-space helpers: luminance, YCoCg (TAA clamp space), display transform.
#pragma once
#include "core/vec.h"

namespace bmfr {

/// Rec. 709 relative luminance of linear RGB.
BMFR_HD float luminance(Vec3 c) {
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

/// Unnormalised YCoCg as in the authors' TAA; inverse below.
BMFR_HD Vec3 rgbToYCoCg(Vec3 c) {
    return {c.x + 2.0f * c.y + c.z, 2.0f * c.x - 2.0f * c.z, -c.x + 2.0f * c.y - c.z};
}
BMFR_HD Vec3 yCoCgToRgb(Vec3 c) {
    return {0.25f * (c.x + c.y - c.z), 0.25f * (c.x + c.z), 0.25f * (c.x - c.y - c.z)};
}

/// The paper's display transform: clamp(x^(1/2.2), 0, 1) of linear radiance.
BMFR_HD float gammaEncode(float v) {
    v = v > 0.0f ? std::pow(v, 1.0f / 2.2f) : 0.0f;
    return v < 1.0f ? v : 1.0f;
}
BMFR_HD Vec3 gammaEncode(Vec3 c) {
    return {gammaEncode(c.x), gammaEncode(c.y), gammaEncode(c.z)};
}
/// The inverse of gammaEncode on [0, 1]: x^2.2 (0 below 0, where a display shows black).
BMFR_HD float gammaDecode(float v) {
    return v > 0.0f ? std::pow(v, 2.2f) : 0.0f;
}
BMFR_HD Vec3 gammaDecode(Vec3 v) {
    return {gammaDecode(v.x), gammaDecode(v.y), gammaDecode(v.z)};
}

} // namespace bmfr
