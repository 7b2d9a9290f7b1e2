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
    /// Stepped tracing (WalrSettings::edgeStep; with tracing, when > 0): the share of the flat
    /// run found ahead by the last iteration that a step skips. 0 = every pixel.
    float stepFraction = 0;
    /// Whether the trace steps (stepFraction above 0, with tracing).
    BMFR_HD bool stepped() const { return tracing && stepFraction > 0; }
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

/// Pixels of a row step together in aligned runs of this many (the CPU backend's lanes): a
/// stepped trace's schedule is its run's.
constexpr int kTraceRun = 8;

/// A stepped trace's state per tap direction and pixel, at [tap * pixels + i], carried from
/// one iteration to the next: the traced minimum, the first step where it is 0 (0 = none yet)
/// and the flat run (the last step where it is still 1). The runs are double-buffered, since a
/// step reads the last iteration's at the pixels it reaches.
struct SteppedTrace {
    float* min = nullptr;
    int32_t* firstZero = nullptr;
    const uint8_t* flatBefore = nullptr; ///< the last iteration's runs; null at iteration 0
    uint8_t* flat = nullptr;
    long pixels = 0;
};

/// The steps a stepped trace skips after a flat run of `run` steps: fraction x run.
BMFR_HD int skipOverRun(float fraction, int run) {
    return int(fraction * float(run));
}

/// How many steps a stepped trace skips after step `anchor` of the tap (ux, uy) of pixel
/// (x, y): skipOverRun of the shortest flat run that the last iteration's traces found along
/// the same direction from the pixels that step reaches from the run of (x, y) (those inside
/// the image). `flatBefore` is that direction's plane of runs.
BMFR_HD int traceSkip(const EdgeGuide& g, const uint8_t* flatBefore, int x, int y, int ux, int uy,
                      int anchor) {
    const int x0 = x - x % kTraceRun;
    const long row = long(y + anchor * uy) * g.width;
    int shortest = 255;
    for (int r = x0; r < x0 + kTraceRun; ++r) {
        const int qx = r + anchor * ux;
        if (qx < 0 || qx >= g.width) continue;
        const int run = flatBefore[row + qx];
        shortest = run < shortest ? run : shortest;
    }
    return skipOverRun(g.stepFraction, shortest);
}

/// One step of a stepped trace at step k: false once the minimum m reaches 0 (firstZero = k);
/// flat = k while it is still 1.
BMFR_HD bool stepOn(const EdgeGuide& g, const EdgeCentre& c, int x, int y, int ux, int uy, int k,
                    float& m, int& firstZero, int& flat) {
    const float w = edgeWeight(c, load3(g.position, long(y + k * uy) * g.width + x + k * ux));
    m = w < m ? w : m;
    if (m <= 0.0f) {
        firstZero = k;
        return false;
    }
    if (m >= 1.0f) flat = k;
    return true;
}

/// The steps of the tap (ux, uy) of pixel (x, y) beyond the last iteration's, stepped by the
/// distances that iteration traced (the paper's distance-field steps), on from the carried
/// minimum m, first zero and flat run; stops at the first zero. The new steps are two stretches
/// as long as the last segment, each beginning where one of the last iteration's segments
/// ended (at `step` / 3 and 2 `step` / 3): the first traceSkip steps of each are skipped and
/// the rest tested, and the tap's own pixel always is. Iteration 0 (flatBefore null) tests
/// its one step.
BMFR_HD void steppedTrace(const EdgeGuide& g, const EdgeCentre& c, const uint8_t* flatBefore, int x,
                          int y, int ux, int uy, int step, float& m, int& firstZero, int& flat) {
    if (!(m > 0.0f)) return;
    if (!flatBefore) {
        for (int k = 1; k <= step; ++k)
            if (!stepOn(g, c, x, y, ux, uy, k, m, firstZero, flat)) return;
        return;
    }
    const int third = step / 3;
    for (int anchor = third; anchor < step; anchor += third) {
        int from = anchor + 1 + traceSkip(g, flatBefore, x, y, ux, uy, anchor);
        if (from > step) from = step;
        for (int k = from; k <= anchor + third; ++k)
            if (!stepOn(g, c, x, y, ux, uy, k, m, firstZero, flat)) return;
    }
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

/// A tap whose traced minimum is w, with its first zero at step `edge`: itself when w > 0;
/// else, when replacement is on and edge > 1, the pixel at a step drawn uniformly from
/// [1, edge - 1] by `hash`, weighted by the traced minimum over every step up to it.
BMFR_HD TracedTap keptOrReplaced(const EdgeGuide& g, const EdgeCentre& c, int x, int y, int ux,
                                 int uy, int step, float w, int edge, uint32_t hash) {
    if (w > 0) return {w, step};
    if (!g.replacement || edge <= 1) return {};
    const int k = replacementStep(hash, edge);
    int unused = 0;
    return {tracedWeight(g, c, x, y, ux, uy, k, unused), k};
}

/// The tap at step * (ux, uy) from (x, y). Outside the image it is dropped. Without tracing only
/// its end is tested. With tracing, a tap whose segment meets an edge (weight 0 at step k_e) is
/// replaced (keptOrReplaced).
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
    return keptOrReplaced(g, c, x, y, ux, uy, step, w, edge, hash);
}

/// traceTap with stepped tracing: tap `tap` of pixel i = (x, y) at iteration `iteration`
/// continues the trace carried in s from the last iteration's step (steppedTrace) and leaves
/// it there. A dropped tap's flat run is 0.
BMFR_HD TracedTap traceTapStepped(const EdgeGuide& g, const EdgeCentre& c, const SteppedTrace& s,
                                  long i, int tap, int x, int y, int ux, int uy, int iteration,
                                  int step, uint32_t hash) {
    const long at = tap * s.pixels + i;
    const int ex = x + step * ux, ey = y + step * uy;
    if (ex < 0 || ey < 0 || ex >= g.width || ey >= g.height) {
        s.flat[at] = 0;
        return {};
    }
    const bool carried = iteration > 0;
    float m = carried ? s.min[at] : 1.0f;
    int edge = carried ? s.firstZero[at] : 0;
    int flat = carried ? s.flatBefore[at] : 0;
    const uint8_t* before = carried ? s.flatBefore + tap * s.pixels : nullptr;
    steppedTrace(g, c, before, x, y, ux, uy, step, m, edge, flat);
    s.min[at] = m;
    s.firstZero[at] = edge;
    s.flat[at] = uint8_t(flat);
    return keptOrReplaced(g, c, x, y, ux, uy, step, m, edge, hash);
}

/// The hash of a replacement choice: pixel, frame, iteration, tap and the user's seed; of a
/// vector of pixels too (the CPU backend's), as hashKeysOf.
template <class U>
BMFR_HD U replacementHashOf(U pixel, uint32_t frame, int iteration, int tap, uint32_t seed) {
    return hashKeysOf(pixel, U{} + frame, U{} + uint32_t(iteration * 8 + tap), U{} + seed);
}
BMFR_HD uint32_t replacementHash(long pixel, uint32_t frame, int iteration, int tap,
                                 uint32_t seed) {
    return replacementHashOf(uint32_t(pixel), frame, iteration, tap, seed);
}

} // namespace bmfr
