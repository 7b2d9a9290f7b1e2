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
/// Karis's reversible range compression c / (1 + max(r, g, b)): radiance in [0, inf) to [0, 1),
/// so that a blend of a light's pixel with its neighbours weighs it as a display does, and
/// back with expandRange (no clipping). Negative maxima count as 0.
BMFR_HD Vec3 compressRange(Vec3 c) {
    float m = c.x > c.y ? c.x : c.y;
    m = m > c.z ? m : c.z;
    return c / (1.0f + (m > 0.0f ? m : 0.0f));
}
/// The inverse of compressRange: v / (1 - max(r, g, b)), the divisor kept at least 1/65536
/// (radiance 65535 and above comes back as 65535).
BMFR_HD Vec3 expandRange(Vec3 v) {
    float m = v.x > v.y ? v.x : v.y;
    m = m > v.z ? m : v.z;
    const float d = 1.0f - (m > 0.0f ? m : 0.0f);
    return v / (d > 1.0f / 65536.0f ? d : 1.0f / 65536.0f);
}
/// The inverse of gammaEncode on [0, 1]: x^2.2 (0 below 0, where a display shows black).
BMFR_HD float gammaDecode(float v) {
    return v > 0.0f ? std::pow(v, 2.2f) : 0.0f;
}
BMFR_HD Vec3 gammaDecode(Vec3 v) {
    return {gammaDecode(v.x), gammaDecode(v.y), gammaDecode(v.z)};
}

} // namespace bmfr
