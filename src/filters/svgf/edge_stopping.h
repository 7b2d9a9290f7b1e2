// SVGF's edge-stopping weights (Schied et al. 2017, eq. 3-5) and kernels: per-pixel math shared
// by every backend.
#pragma once
#include "core/vec.h"
#include <cmath>

namespace bmfr {

/// Depth weight: exp(-|z0 - z1| / (sigma_z |grad z . offset| + eps)).
BMFR_HD float depthWeight(float z0, float z1, Vec2 gradient, float dx, float dy, float sigmaZ) {
    const float slope = std::fabs(gradient.x * dx + gradient.y * dy);
    return std::exp(-std::fabs(z0 - z1) / (sigmaZ * slope + 1e-6f));
}

/// Normal weight: max(0, n0 . n1)^sigma_n (repeated squaring for integer exponents).
BMFR_HD float normalWeight(Vec3 n0, Vec3 n1, float sigmaN) {
    const float c = std::fmax(0.0f, dot(n0, n1));
    const int e = int(sigmaN);
    if (float(e) != sigmaN) return std::pow(c, sigmaN);
    float result = 1.0f, base = c;
    for (int k = e; k > 0; k >>= 1, base *= base)
        if (k & 1) result *= base;
    return result;
}

/// The exponent arguments of the depth and luminance weights, so one exp serves both.
BMFR_HD float depthArgument(float z0, float z1, Vec2 gradient, float dx, float dy, float sigmaZ) {
    return std::fabs(z0 - z1) / (sigmaZ * std::fabs(gradient.x * dx + gradient.y * dy) + 1e-6f);
}
/// Denominator of the luminance weight for a centre pixel with (prefiltered) variance.
BMFR_HD float luminanceDenominator(float variance, float sigmaL) {
    return sigmaL * std::sqrt(std::fmax(variance, 0.0f)) + 1e-10f;
}

/// 1-D taps of the a-trous kernel: B3 spline (radius 2) or its 3x3 reduction (radius 1).
BMFR_HD float atrousTap(int radius, int offset) {
    const int a = offset < 0 ? -offset : offset;
    if (radius == 1) return a == 0 ? 0.5f : 0.25f;
    return a == 0 ? 0.375f : (a == 1 ? 0.25f : 0.0625f);
}

} // namespace bmfr
