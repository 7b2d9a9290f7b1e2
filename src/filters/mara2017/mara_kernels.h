// Mara et al. 2017's per-pixel maths, BMFR_HD, written once for every backend: the confidence
// of Eq. 11, the bilateral edge weights, the sparse spiral taps, the median, the
// glossy sigma and the composition. The stage bodies over a frame's buffers are in
// mara_stages.h.
#pragma once
#include "core/hash.h"
#include "temporal/pixel_input.h"
#include <cstdint>

namespace bmfr {

BMFR_HD float maraSmoothstep(float e0, float e1, float x) {
    float t = (x - e0) / (e1 - e0);
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    return t * t * (3.0f - 2.0f * t);
}

/// Stage 3's confidence, their Eq. 11 with the sign the text means ("a smooth transition at
/// 6 cm from 0 to 95% hysteresis"): h for a perfect reprojection, falling to 0 from d0 to d1.
/// Read literally, the printed h * smoothstep(d0, d1, distance) trusts the largest mismatches.
BMFR_HD float maraConfidence(float distance, float h, float d0, float d1) {
    if (!(distance >= 0.0f)) return 0.0f; // NaN: no history
    return h * (1.0f - maraSmoothstep(d0, d1, distance));
}

/// The cross-bilateral edge terms every stage shares (the G3D lineage of the paper's "camera-
/// space plane distance in normals and depth").
struct MaraEdgeWeights {
    float normal = 1.0f;            ///< k_n
    float plane = 1.0f;             ///< k_p
    float planeNearSquared = 1e-3f; ///< taps nearer than this (squared) keep full plane weight
};

/// Edge weight of tap q for centre c: normal max(0, 1 - k_n (1 - max(0, n_c.n_q)^4)) times plane
/// max(0, 1 - 2 k_p max(|dp.n_q|, |dp.n_c|) / |dp|)^2, dp = p_q - p_c.
BMFR_HD float maraEdgeWeight(Vec3 nc, Vec3 pc, Vec3 nq, Vec3 pq, const MaraEdgeWeights& k) {
    float cn = dot(nc, nq);
    cn = cn > 0.0f ? cn : 0.0f;
    const float c2 = cn * cn;
    float w = 1.0f - k.normal * (1.0f - c2 * c2);
    if (!(w > 0.0f)) return 0.0f;
    const Vec3 dp = pq - pc;
    const float d2 = dot(dp, dp);
    if (d2 >= k.planeNearSquared) {
        const float along = std::fmax(std::fabs(dot(dp, nq)), std::fabs(dot(dp, nc)));
        float wp = 1.0f - 2.0f * k.plane * along / std::sqrt(d2);
        wp = wp > 0.0f ? wp : 0.0f;
        w *= wp * wp;
    }
    return w;
}

/// Spiral turns of the sparse taps: coprime with the paper's 50 taps, 19/50 near 1/golden^2.
inline constexpr int kMaraSpiralTurns = 19;
/// Rotations of the spiral a pixel picks from each frame (hashed from pixel and frame).
inline constexpr int kMaraSpiralRotations = 16;

/// Unit-disk offset of tap k of `taps` (Mara et al. 2016's AO spiral): radius (k + 0.5) / taps,
/// angle 2 pi turns (k + 0.5) / taps + rotation.
BMFR_HD Vec2 maraSpiralTap(int k, int taps, float rotation) {
    const float a = (float(k) + 0.5f) / float(taps);
    const float angle = 6.28318531f * float(kMaraSpiralTurns) * a + rotation;
    return {a * std::cos(angle), a * std::sin(angle)};
}

/// The whole spiral's rotation for one frame (same for every pixel), radians.
BMFR_HD float maraFrameRotation(uint32_t frame, uint32_t seed, uint32_t stage) {
    return 6.28318531f * unitFloat(hashKeys(frame, seed, stage, 0x6d617261u));
}

/// Which of the kMaraSpiralRotations a pixel uses this frame: hashed from the pixel's run of
/// `across` pixels on its row (1: its own), its row and the frame.
BMFR_HD int maraPixelRotation(int x, int y, int across, uint32_t frame, uint32_t seed,
                              uint32_t stage) {
    return int(hashKeys(uint32_t(x / across), uint32_t(y), frame, seed * 4u + stage) %
               uint32_t(kMaraSpiralRotations));
}

/// A tap's whole-pixel offset: the unit offset times the radius, rounded to nearest (one
/// product, so every backend rounds it alike).
BMFR_HD int maraTapOffset(float unit, float radius) {
    return int(std::nearbyint(unit * radius));
}

/// The exponent of maraGaussian: the CPU backend takes its exponentials eight at a time.
BMFR_HD float maraGaussianExponent(float d2, float sigma) {
    return -d2 / (2.0f * sigma * sigma);
}

BMFR_HD float maraGaussian(float d2, float sigma) {
    return std::exp(maraGaussianExponent(d2, sigma));
}

/// Stages 9-10: sigma = scale * roughness^exponent + epsilon pixels, independent of resolution.
BMFR_HD float maraGlossySigma(float roughness, float scale, float exponent, float epsilon) {
    const float r = roughness > 0.0f ? (roughness < 1.0f ? roughness : 1.0f) : 0.0f;
    return scale * std::pow(r, exponent) + epsilon;
}

/// Median of nine values (a partial sort network: only the middle is kept).
BMFR_HD float maraMedian9(float v[9]) {
    for (int i = 0; i <= 4; ++i) {
        int m = i;
        for (int j = i + 1; j < 9; ++j)
            if (v[j] < v[m]) m = j;
        const float t = v[i];
        v[i] = v[m];
        v[m] = t;
    }
    return v[4];
}

/// Schlick's Fresnel at the mirror direction, where the half vector is the normal: F_s.
BMFR_HD Vec3 maraFresnel(Vec3 f0, float cosine) {
    const float m = 1.0f - (cosine > 0.0f ? (cosine < 1.0f ? cosine : 1.0f) : 0.0f);
    const float m2 = m * m, k = m2 * m2 * m;
    return f0 + k * (Vec3{1, 1, 1} - f0);
}

/// Their Eq. 9 and 10 with m = rho / pi: L = direct + (1 - F_s)^2 rho M + F_s G + emission.
BMFR_HD Vec3 maraCompose(Vec3 direct, Vec3 rho, Vec3 fresnel, Vec3 matte, Vec3 glossy,
                         Vec3 emission) {
    const Vec3 m = Vec3{1, 1, 1} - fresnel;
    return direct + m * m * rho * matte + fresnel * glossy + emission;
}

} // namespace bmfr
