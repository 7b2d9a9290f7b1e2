// History rectification by variance clipping (Salvi 2016): the history is pulled along the line
// to the neighbourhood mean until it lies inside mean +- gamma * standard deviation. Unlike a
// min/max clamp it keeps the hue of the history and is not widened by one outlier.
#pragma once
#include "core/vec.h"
#include <cmath>

namespace bmfr {

/// Mean and standard deviation of a 3x3 neighbourhood, per channel.
struct NeighbourhoodMoments {
    Vec3 mean, deviation;
};

/// Moments of the 3x3 around (x, y) of a packed 3-channel image; taps outside are skipped.
BMFR_HD NeighbourhoodMoments neighbourhoodMoments(const float* img, int width, int height, int x,
                                                  int y) {
    Vec3 s1{}, s2{};
    float n = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= width || qy >= height) continue;
            const Vec3 v = load3(img, long(qy) * width + qx);
            s1 += v;
            s2 += v * v;
            n += 1.0f;
        }
    NeighbourhoodMoments m;
    m.mean = s1 / n;
    const Vec3 var = s2 / n - m.mean * m.mean;
    m.deviation = {std::sqrt(std::fmax(var.x, 0.0f)), std::sqrt(std::fmax(var.y, 0.0f)),
                   std::sqrt(std::fmax(var.z, 0.0f))};
    return m;
}

/// `history` clipped towards m.mean into the box mean +- gamma * deviation; a history inside
/// the box is returned unchanged.
BMFR_HD Vec3 varianceClip(Vec3 history, const NeighbourhoodMoments& m, float gamma) {
    const Vec3 d = history - m.mean, extent = gamma * m.deviation;
    float t = 1.0f;
    for (int c = 0; c < 3; ++c) {
        const float a = std::fabs(d[c]);
        if (a > extent[c]) t = std::fmin(t, extent[c] / a);
    }
    return m.mean + t * d;
}

} // namespace bmfr
