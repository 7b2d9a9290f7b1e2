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

/// The 3-channel images `a` and `b` (packed, width x height) sampled at continuous pixel `p`
/// (integers are pixel centres) with the same weights (b may be null), taps clamped to the image's
/// edge. Catmull-Rom overshoots next to steps, so the results are clamped to >= 0 (the filtered
/// signals are radiance).
BMFR_HD void sampleCatmullRom2(const float* a, const float* b, int width, int height, Vec2 p,
                               Vec3& outA, Vec3& outB) {
    const float bx = std::floor(p.x), by = std::floor(p.y);
    float wx[4], wy[4];
    catmullRomWeights(p.x - bx, wx);
    catmullRomWeights(p.y - by, wy);
    const int x0 = int(bx) - 1, y0 = int(by) - 1;
    int xs[4];
    for (int i = 0; i < 4; ++i) {
        const int x = x0 + i;
        xs[i] = x < 0 ? 0 : (x >= width ? width - 1 : x);
    }
    Vec3 sumA{}, sumB{};
    for (int j = 0; j < 4; ++j) {
        int y = y0 + j;
        y = y < 0 ? 0 : (y >= height ? height - 1 : y);
        const long row = long(y) * width;
        Vec3 rowA{}, rowB{};
        for (int i = 0; i < 4; ++i) {
            rowA += wx[i] * load3(a, row + xs[i]);
            if (b) rowB += wx[i] * load3(b, row + xs[i]);
        }
        sumA += wy[j] * rowA;
        sumB += wy[j] * rowB;
    }
    outA = vmax(sumA, Vec3{0, 0, 0});
    outB = vmax(sumB, Vec3{0, 0, 0});
}

} // namespace bmfr
