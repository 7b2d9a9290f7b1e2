// Reprojection of a surface point into the previous frame and the per-tap discard test.
// Shared by every temporal filter (BMFR phases I and III, TAA, SVGF): one implementation.
#pragma once
#include "core/mat4.h"
#include "temporal/history.h"
#include "temporal/pixel_input.h"
#include <cstdint>

namespace bmfr {

/// Continuous pixel coordinate of world point p in a frame with view-projection `vp` and
/// primary-ray offset `jitter`: integer values are that frame's sample positions (pixel
/// centres). Returns false when p is behind the camera or the result is not finite.
BMFR_HD bool projectToPixel(const Mat4& vp, Vec3 p, const float jitter[2], int width, int height,
                            Vec2& pixel) {
    Vec4 c = transformPoint(vp, p);
    if (!(c.w > 0.0f)) return false;
    pixel.x = (c.x / c.w * 0.5f + 0.5f) * float(width) - 0.5f - jitter[0];
    pixel.y = (c.y / c.w * 0.5f + 0.5f) * float(height) - 0.5f - jitter[1];
    return std::isfinite(pixel.x) && std::isfinite(pixel.y) && std::fabs(pixel.x) < 1e8f &&
           std::fabs(pixel.y) < 1e8f;
}

/// Pixel i's surface as the previous frame saw it: where it was, and the position and normal
/// that the discard test compares with the previous frame's buffers.
struct PreviousSurface {
    Vec2 pixel{-1e6f, -1e6f}; ///< continuous pixel; out of every image when there is none
    Vec3 position, normal;
};

/// Where pixel i (at x, y) with current surface (p, n) was in the previous frame: through the
/// frame's motion vector when it has one, else by projecting its previous position (or, without
/// one, its current position) with the previous camera. The previous position and normal stand
/// in for p and n in the discard test when the frame has them. Non-finite values are counted in
/// `bad` on every frame; a non-finite motion vector means no history, a non-finite previous
/// position or normal is replaced by 0. Returns false when there is no previous pixel.
BMFR_HD bool findPreviousSurface(const InputPlanes& in, long i, int x, int y, Vec3 p, Vec3 n,
                                 const PreviousFrame& prev, int64_t& bad, PreviousSurface& s) {
    s.position = in.previousPosition ? finiteOrZero(load3(in.previousPosition, i), bad) : p;
    s.normal = in.previousNormal ? finiteOrZero(load3(in.previousNormal, i), bad) : n;
    s.pixel = {-1e6f, -1e6f};
    if (in.motion) {
        const float mx = in.motion[2 * i], my = in.motion[2 * i + 1];
        const bool finite = std::isfinite(mx) && std::isfinite(my);
        bad += int64_t(!std::isfinite(mx)) + int64_t(!std::isfinite(my));
        if (!prev.valid || !finite) return false;
        const Vec2 pixel{float(x) + mx, float(y) + my};
        if (!(std::fabs(pixel.x) < 1e8f && std::fabs(pixel.y) < 1e8f)) return false;
        s.pixel = pixel;
        return true;
    }
    if (!prev.valid) return false;
    Vec2 pixel;
    if (!projectToPixel(prev.viewProjection, s.position, prev.jitter, in.width, in.height, pixel))
        return false;
    s.pixel = pixel;
    return true;
}

/// The 2x2 bilinear footprint of a continuous pixel coordinate: taps (0,0), (1,0), (0,1),
/// (1,1) from (x0, y0), in that order (bit i of an accept mask is tap i).
struct BilinearFootprint {
    int x0 = 0, y0 = 0;
    float weight[4] = {0, 0, 0, 0};
};

BMFR_HD BilinearFootprint bilinearFootprint(Vec2 pixel) {
    BilinearFootprint f;
    float fx = std::floor(pixel.x), fy = std::floor(pixel.y);
    f.x0 = int(fx), f.y0 = int(fy);
    float ax = pixel.x - fx, ay = pixel.y - fy;
    f.weight[0] = (1 - ax) * (1 - ay);
    f.weight[1] = ax * (1 - ay);
    f.weight[2] = (1 - ax) * ay;
    f.weight[3] = ax * ay;
    return f;
}

BMFR_HD int tapX(const BilinearFootprint& f, int tap) {
    return f.x0 + (tap & 1);
}
BMFR_HD int tapY(const BilinearFootprint& f, int tap) {
    return f.y0 + (tap >> 1);
}

/// Thresholds of the history discard test.
struct DiscardLimits {
    float positionSquared = 0.01f; ///< scene units squared
    float normalSquared = 1.0f;    ///< squared distance of unit normals
};

/// Tests each tap of the previous frame against the current surface (p, n): inside the image,
/// squared position distance and squared normal distance below the limits. Returns the mask.
/// The normals are floats, or halves (core/half.h) where a history keeps them so.
template <class N>
BMFR_HD uint8_t acceptTaps(const BilinearFootprint& f, Vec3 p, Vec3 n, const float* prevPositions,
                           const N* prevNormals, int width, int height,
                           const DiscardLimits& limits) {
    uint8_t accept = 0;
    for (int t = 0; t < 4; ++t) {
        int x = tapX(f, t), y = tapY(f, t);
        if (x < 0 || y < 0 || x >= width || y >= height) continue;
        long i = long(y) * width + x;
        Vec3 dp = load3(prevPositions, i) - p;
        if (!(dot(dp, dp) < limits.positionSquared)) continue;
        Vec3 dn = load3(prevNormals, i) - n;
        if (!(dot(dn, dn) < limits.normalSquared)) continue;
        accept |= uint8_t(1u << t);
    }
    return accept;
}

/// Bilinear weight of each accepted tap passed to fetch(pixelIndex, weight); returns the sum of
/// accepted weights, by which the caller normalises (so discarded taps do not darken).
template <typename Fetch>
BMFR_HD float gatherAccepted(const BilinearFootprint& f, uint8_t accept, int width, Fetch&& fetch) {
    float total = 0.0f;
    for (int t = 0; t < 4; ++t) {
        if (!(accept & (1u << t))) continue;
        fetch(long(tapY(f, t)) * width + tapX(f, t), f.weight[t]);
        total += f.weight[t];
    }
    return total;
}

} // namespace bmfr
