// Fireflies (BmfrSettings::clampFireflies): a long path's rare bright sample, once accumulated,
// is a pixel or two far above its block, and the least squares spread it through the block. In
// the fit's input, a pixel above kFireflyRatio times the block's median whose neighbours are
// mostly not (three of eight at most: a firefly smeared over 2x2 by the reprojection) and none
// of them inside a bright patch is scaled down to that level. Bright patches, lit surfaces and
// emitters, keep theirs; a bright line one pixel wide does not. Only the fit's
// input changes: the accumulated history keeps the sample's energy.
// The clamp fades out as a pixel's history grows (fireflyFade): where the history is long the
// accumulated value is an average whose bright samples are the estimator's own tail, and
// phase III averages the fit again. Clamping there biased a dark, indirectly lit surface low
// (the still room's box face, 10% below the reference) and made it flicker, as the share
// clamped changed from frame to frame.
#pragma once
#include "core/color.h"
#include "filters/bmfr/emitter_exclusion.h"

namespace bmfr {

/// The multiple of the block's median (emitter_exclusion.h's) above which a pixel may be a
/// firefly.
inline constexpr float kFireflyRatio = 8.0f;

inline constexpr uint8_t kFireflyCandidate = 1, kFireflyDense = 2;

/// Stage 1, block pixel k: above the threshold.
BMFR_HD uint8_t fireflyCandidate(float lum, float threshold) {
    return threshold > 0.0f && lum > threshold ? kFireflyCandidate : 0;
}

/// Stage 2, block pixel k: a candidate with five or more candidate neighbours is inside a
/// bright patch.
BMFR_HD uint8_t fireflyDense(const uint8_t* mask, int B, int k) {
    return (mask[k] & kFireflyCandidate) && maskNeighbours(mask, B, k, kFireflyCandidate) >= 5
               ? kFireflyDense
               : 0;
}

/// Stage 3, block pixel k: the factor its colour is scaled by; below 1 for a candidate with at
/// most three candidate neighbours and none inside a patch (a patch's corner has three).
BMFR_HD float fireflyScale(const uint8_t* mask, int B, int k, float lum, float threshold) {
    if (!(mask[k] & kFireflyCandidate) || (mask[k] & kFireflyDense)) return 1.0f;
    if (maskNeighbours(mask, B, k, kFireflyCandidate) > 3) return 1.0f;
    return maskNeighbours(mask, B, k, kFireflyDense) > 0 ? 1.0f : threshold / lum;
}

/// The history length (samples) from which a pixel is not clamped at all: phase I's default
/// 1 / firstBlendAlpha, where its weight on a new sample has come down to its floor.
inline constexpr float kFireflyFadeLength = 5.0f;

/// Stage 4, a scale from fireflyScale for a pixel whose history holds `length` samples: the
/// full clamp without history (1 sample), none from kFireflyFadeLength, linear between.
BMFR_HD float fireflyFade(float scale, float length) {
    if (!(scale < 1.0f)) return scale;
    const float t = (length - 1.0f) / (kFireflyFadeLength - 1.0f);
    if (!(t > 0.0f)) return scale;
    return t < 1.0f ? scale + (1.0f - scale) * t : 1.0f;
}

/// clampFireflies of a block whose threshold (kFireflyRatio times its median's top) is known;
/// lum(k) is block pixel k's luminance before the clamp. A backend that has the luminances
/// at hand calls it directly.
template <class Lum, class Length>
BMFR_HD int clampFirefliesAbove(int B, float* const z[3], uint8_t* mask, float threshold, Lum&& lum,
                                Length&& length) {
    const int W = B * B;
    if (!(threshold > 0.0f)) return 0;
    // Most blocks have no candidate: a loop that only counts them (it vectorises) says so.
    int candidates = 0;
    for (int k = 0; k < W; ++k) candidates += fireflyCandidate(lum(k), threshold);
    if (candidates == 0) return 0;
    for (int k = 0; k < W; ++k) mask[k] = fireflyCandidate(lum(k), threshold);
    for (int k = 0; k < W; ++k) mask[k] |= fireflyDense(mask, B, k);
    int clamped = 0;
    for (int k = 0; k < W; ++k) {
        // The mask's bits were all set before any scaling, and a pixel's own luminance is read
        // before its own scaling.
        float f = fireflyScale(mask, B, k, lum(k), threshold);
        if (f == 1.0f) continue;
        f = fireflyFade(f, length(k));
        if (f == 1.0f) continue;
        for (int c = 0; c < 3; ++c) z[c][k] *= f;
        ++clamped;
    }
    return clamped;
}

/// Clamps the fireflies of a B x B block's colour columns z[3] (W values each), with `mask`
/// (W bytes) and `histogram` as scratch; length(k) is block pixel k's history length (phase I's
/// samples), read for the pixels the clamp would scale. Returns how many it scales, and with
/// `quartile` the block's lower-quartile bucket, which the emitter mask reads, from the same
/// count. The clamp leaves it unchanged: a scaled pixel stays above kFireflyRatio times the
/// median's top, so as many pixels as before lie at or below each bucket up to the median's.
template <class Length>
BMFR_HD int clampFireflies(int B, float* const z[3], int* histogram, uint8_t* mask, Length&& length,
                           int* quartile = nullptr) {
    const int W = B * B;
    // Local copies of the planes: through z[], every mask store below would reload them.
    const float *r = z[0], *g = z[1], *b = z[2];
    auto lum = [=](int k) { return luminance({r[k], g[k], b[k]}); };
    const int bucket = blockMedianBucket(W, lum, histogram);
    if (quartile) *quartile = quantileBucket(histogram, W / kMaskStride, kEmitterQuantile);
    return clampFirefliesAbove(B, z, mask, bucketThreshold(bucket, kFireflyRatio), lum, length);
}

} // namespace bmfr
