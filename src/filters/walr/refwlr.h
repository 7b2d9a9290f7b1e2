// REFWLR, the paper's reference solver (section 6): the same features, edge weights and window
// as WALR, but a direct weighted regression over every pixel of the 3^T x 3^T window, each traced
// from the centre along its own digital line, with no a-trous and no replacement. Double
// precision; slow by design (it is the oracle of WALR's approximations).
#pragma once
#include "filters/walr/atrous_averages.h"
#include <cmath>

namespace bmfr {

/// The traced weight of the pixel at (x + dx, y + dy): the smallest edge weight at the points
/// round(k (dx, dy) / L), k = 1 .. L = max(|dx|, |dy|); with tracing off, its own weight.
BMFR_HD float refwlrTracedWeight(const EdgeGuide& g, const EdgeCentre& c, int x, int y, int dx,
                                 int dy) {
    const int steps = std::abs(dx) > std::abs(dy) ? std::abs(dx) : std::abs(dy);
    if (!g.tracing) return edgeWeight(c, load3(g.position, long(y + dy) * g.width + x + dx));
    float m = 1.0f;
    for (int k = 1; k <= steps && m > 0.0f; ++k) {
        const int qx = x + int(std::floor(double(k) * dx / steps + 0.5));
        const int qy = y + int(std::floor(double(k) * dy / steps + 0.5));
        const float w = edgeWeight(c, load3(g.position, long(qy) * g.width + qx));
        m = w < m ? w : m;
    }
    return m > 0.0f ? m : 0.0f;
}

/// REFWLR at pixel (x, y) over the window of half-width `radius`, clipped to the image: signal
/// has 3 floats per pixel, features 2.
BMFR_HD Vec3 refwlrPixel(const EdgeGuide& g, const float* signal, const float* features, int radius,
                         double eps, int x, int y) {
    const EdgeCentre c = edgeCentre(g, long(y) * g.width + x);
    double sum[kWalrAverages] = {};
    double total = 0;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if (qx < 0 || qy < 0 || qx >= g.width || qy >= g.height) continue;
            const double w = (dx == 0 && dy == 0) ? 1.0 : refwlrTracedWeight(g, c, x, y, dx, dy);
            if (!(w > 0)) continue;
            const long j = long(qy) * g.width + qx;
            const double u = features[2 * j], v = features[2 * j + 1];
            const double s[kWalrAverages] = {u,
                                             v,
                                             u * u,
                                             u * v,
                                             v * v,
                                             signal[3 * j],
                                             signal[3 * j] * u,
                                             signal[3 * j] * v,
                                             signal[3 * j + 1],
                                             signal[3 * j + 1] * u,
                                             signal[3 * j + 1] * v,
                                             signal[3 * j + 2],
                                             signal[3 * j + 2] * u,
                                             signal[3 * j + 2] * v};
            for (int k = 0; k < kWalrAverages; ++k) sum[k] += w * s[k];
            total += w;
        }
    for (double& s : sum) s /= total;
    const long i = long(y) * g.width + x;
    return walrPredict<double>(sum, {features[2 * i], features[2 * i + 1]}, eps);
}

} // namespace bmfr
