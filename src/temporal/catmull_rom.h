// Bicubic (Catmull-Rom) resampling of a history image at a continuous pixel position: sharper
// than bilinear, so a history resampled every frame does not blur. Per pixel and BMFR_HD.
#pragma once
#include "core/vec.h"
#include <cmath>

namespace bmfr {

/// The four Catmull-Rom weights of taps floor(p) - 1 .. floor(p) + 2 for fraction f in [0, 1).
BMFR_HD void catmullRomWeights(float f, float w[4]) {
    w[0] = f * (-0.5f + f * (1.0f - 0.5f * f));
    w[1] = 1.0f + f * f * (-2.5f + 1.5f * f);
    w[2] = f * (0.5f + f * (2.0f - 1.5f * f));
    w[3] = f * f * (-0.5f + 0.5f * f);
}

/// The 3-channel image `img` (packed, width x height) sampled at continuous pixel `p` (integers
/// are pixel centres), taps clamped to the image's edge. Catmull-Rom overshoots next to steps,
/// so the result is clamped to >= 0 (the filtered signals are radiance).
BMFR_HD Vec3 sampleCatmullRom(const float* img, int width, int height, Vec2 p) {
    const float bx = std::floor(p.x), by = std::floor(p.y);
    float wx[4], wy[4];
    catmullRomWeights(p.x - bx, wx);
    catmullRomWeights(p.y - by, wy);
    const int x0 = int(bx) - 1, y0 = int(by) - 1;
    Vec3 sum{};
    for (int j = 0; j < 4; ++j) {
        int y = y0 + j;
        y = y < 0 ? 0 : (y >= height ? height - 1 : y);
        Vec3 row{};
        for (int i = 0; i < 4; ++i) {
            int x = x0 + i;
            x = x < 0 ? 0 : (x >= width ? width - 1 : x);
            row += wx[i] * load3(img, long(y) * width + x);
        }
        sum += wy[j] * row;
    }
    return vmax(sum, Vec3{0, 0, 0});
}

} // namespace bmfr
