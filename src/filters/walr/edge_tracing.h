// WALR's edge-stopping function and edge tracing (paper sections 3.3 and 4.3): a tap's weight is
// the smallest plane-distance weight along the segment from the centre to it, so that no thin
// object between them is skipped; a discarded tap may be replaced by a pixel before the edge.
#pragma once
#include "core/hash.h"
#include "core/vec.h"
#include <cmath>
#include <cstdint>

namespace bmfr {

/// What the edge weights read: packed world positions and normals (3 floats per pixel) and view
/// depth (1), and the weight ramp as fractions of the centre's view depth.
struct EdgeGuide {
    const float* position = nullptr;
    const float* normal = nullptr;
    const float* depth = nullptr;
    int width = 0, height = 0;
    float nearFraction = 0.005f, farFraction = 0.02f;
    bool tracing = true, replacement = true;
};

/// The centre's plane and ramp: weight 1 below distance a, 0 from b, linear between.
struct EdgeCentre {
    Vec3 p, n;
    float a = 0, b = 0;
    float slope = 0; ///< 1 / (b - a), or 0 when the ramp is empty
};

/// 1 / (b - a) for a ramp from a to b (0 when b <= a: the ramp is then never evaluated).
BMFR_HD float rampSlope(float a, float b) {
    return b > a ? 1.0f / (b - a) : 0.0f;
}

BMFR_HD EdgeCentre edgeCentre(const EdgeGuide& g, long i) {
    const float z = g.depth[i] > 0 ? g.depth[i] : 0.0f;
    EdgeCentre c{load3(g.position, i), load3(g.normal, i), g.nearFraction * z, g.farFraction * z};
    c.slope = rampSlope(c.a, c.b);
    return c;
}

/// Weight of a pixel at world position q against the centre's plane (the distance is invariant
/// to the rigid view transform, so world space serves as the paper's view space).
BMFR_HD float edgeWeight(const EdgeCentre& c, Vec3 q) {
    const float d = std::fabs(dot(c.n, q - c.p));
    if (!(d > c.a)) return 1.0f;
    if (!(d < c.b)) return 0.0f;
    return (c.b - d) * c.slope;
}

/// Smallest weight at pixels (x + k ux, y + k uy), k = 1 .. steps (all inside the image); stops
/// at the first zero and reports its k in `firstZero` (0 when there is none).
BMFR_HD float tracedWeight(const EdgeGuide& g, const EdgeCentre& c, int x, int y, int ux, int uy,
                           int steps, int& firstZero) {
    float m = 1.0f;
    firstZero = 0;
    for (int k = 1; k <= steps; ++k) {
        const float w = edgeWeight(c, load3(g.position, long(y + k * uy) * g.width + x + k * ux));
        m = w < m ? w : m;
        if (m <= 0.0f) {
            firstZero = k;
            return 0.0f;
        }
    }
    return m;
}

/// A tap after tracing: its weight (0 = dropped) and how many unit steps from the centre along
/// its direction the pixel it reads lies.
struct TracedTap {
    float weight = 0;
    int steps = 0;
};

/// The step a replacement reads, drawn uniformly from [1, edge - 1] by `hash` (edge > 1).
BMFR_HD int replacementStep(uint32_t hash, int edge) {
    return 1 + int(unitFloat(hash) * float(edge - 1));
}

/// The tap at step * (ux, uy) from (x, y). Outside the image it is dropped. Without tracing only
/// its end is tested. With tracing, a tap whose segment meets an edge (weight 0 at step k_e) is
/// replaced, when replacement is on and k_e > 1, by the pixel at a step drawn uniformly from
/// [1, k_e - 1] by `hash`, weighted by the traced minimum up to it.
BMFR_HD TracedTap traceTap(const EdgeGuide& g, const EdgeCentre& c, int x, int y, int ux, int uy,
                           int step, uint32_t hash) {
    const int ex = x + step * ux, ey = y + step * uy;
    if (ex < 0 || ey < 0 || ex >= g.width || ey >= g.height) return {};
    if (!g.tracing) {
        const float w = edgeWeight(c, load3(g.position, long(ey) * g.width + ex));
        return w > 0 ? TracedTap{w, step} : TracedTap{};
    }
    int edge = 0;
    const float w = tracedWeight(g, c, x, y, ux, uy, step, edge);
    if (w > 0) return {w, step};
    if (!g.replacement || edge <= 1) return {};
    const int k = replacementStep(hash, edge);
    int unused = 0;
    return {tracedWeight(g, c, x, y, ux, uy, k, unused), k};
}

/// The hash of a replacement choice: pixel, frame, iteration, tap and the user's seed.
BMFR_HD uint32_t replacementHash(long pixel, uint32_t frame, int iteration, int tap,
                                 uint32_t seed) {
    return hashKeys(uint32_t(pixel), frame, uint32_t(iteration * 8 + tap), seed);
}

} // namespace bmfr
