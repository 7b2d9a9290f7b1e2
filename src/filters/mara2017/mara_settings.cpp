#include "filters/mara2017/mara_settings_table.h"
#include "temporal/temporal_settings_table.h"
#include <bmfr/error.h>
#include <string>

namespace bmfr {

namespace {

using S = Mara2017Settings;

// clang-format off
SettingsTable<S> ownSettings() {
    return {
        {"hysteresis", "mara-hysteresis", "", {0, 1, false, true},
         "h: the history's weight for a perfect reprojection (the paper: 0.98)",
         BMFR_FIELD(S, hysteresis)},
        {"confidenceNear", "mara-confidence-near", "scene units", {0, 1e6},
         "d0: reprojection mismatch where the confidence starts to fall (the paper: 0.05 m)",
         BMFR_FIELD(S, confidenceNear)},
        {"confidenceFar", "mara-confidence-far", "scene units", {0, 1e6, true},
         "d1: reprojection mismatch from which the confidence is 0 (the paper: 0.07 m)",
         BMFR_FIELD(S, confidenceFar)},
        {"cumulativeStart", "mara-cumulative-start", "", {},
         "history weight min(c, n/(n+1)) with n frames of history: a plain average until h takes "
         "over, so the first frame does not keep h^n of the weight (the paper is silent; false = "
         "weight c from the first frame)",
         BMFR_FIELD(S, cumulativeStart)},
        {"clampHistory", "mara-clamp-history", "", {},
         "clamp the matte and glossy histories to the new samples' min/max box",
         BMFR_FIELD(S, clampHistory)},
        {"clampRadius", "mara-clamp-radius", "pixels", {1, 8},
         "the clamp's box reaches this far: 1 = the paper's 3x3, 2 = 5x5 (wider boxes bound a "
         "1-spp history's mean less often below it)",
         BMFR_FIELD(S, clampRadius)},
        {"preBilateral", "mara-pre-bilateral", "", {},
         "stage 4: filter the matte history with the sparse pre-bilateral before storing it",
         BMFR_FIELD(S, preBilateral)},
        {"preTaps", "mara-pre-taps", "taps", {1, 256},
         "stage 4 taps besides the centre (the paper: 50)", BMFR_FIELD(S, preTaps)},
        {"preDiameter", "mara-pre-diameter", "x screen width", {0, 1},
         "stage 4 disk diameter (the paper: 1% of the width, 12.8 px at 1280)",
         BMFR_FIELD(S, preDiameter)},
        {"preSigma", "mara-pre-sigma", "x disk radius", {0, 10, true},
         "stage 4 Gaussian sigma (the paper does not say)", BMFR_FIELD(S, preSigma)},
        {"maxRadius", "mara-max-radius", "x screen width", {0, 1},
         "stage 5 R: the final bilateral's radius where confidence is 0 (the paper: 1/20)",
         BMFR_FIELD(S, maxRadius)},
        {"lowConfidence", "mara-low-confidence", "", {0, 1},
         "stage 5: pixels whose confidence is below this get the boosted radius (the paper: 1/2)",
         BMFR_FIELD(S, lowConfidence)},
        {"radiusBoost", "mara-radius-boost", "x", {1, 100},
         "stage 5 radius multiplier of low-confidence pixels (the paper: 6)",
         BMFR_FIELD(S, radiusBoost)},
        {"normaliseConfidence", "mara-normalise-confidence", "", {},
         "stage 5 reads c / h, so a perfect history gives r = 0 instead of (1 - h) R",
         BMFR_FIELD(S, normaliseConfidence)},
        {"median", "mara-median", "", {},
         "stage 6: the 3x3 firefly median outside the history loop", BMFR_FIELD(S, median)},
        {"finalTaps", "mara-final-taps", "taps", {1, 256},
         "stage 7 taps besides the centre (the paper does not say; stage 4's 50)",
         BMFR_FIELD(S, finalTaps)},
        {"rotationWidth", "mara-rotation-width", "pixels", {1, 64},
         "stages 4 and 7: runs of this many pixels along a row share one of the spiral's 16 "
         "rotations, hashed per run, row and frame; 1 = each pixel its own. 16 lets the CPU read "
         "sixteen neighbours' taps as one vector on AVX-512 (eight elsewhere), with RMSE and "
         "temporal error within 0.4% of 1's (the quality rule's tests)",
         BMFR_FIELD(S, rotationWidth)},
        {"finalSigma", "mara-final-sigma", "x radius", {0, 10, true},
         "stage 7 Gaussian sigma (the paper does not say)", BMFR_FIELD(S, finalSigma)},
        {"virtualReprojection", "mara-virtual-reprojection", "", {},
         "stage 8 reprojects the reflection's virtual position (needs glossyHitDistance), "
         "not the mirror's surface",
         BMFR_FIELD(S, virtualReprojection)},
        {"glossySigmaScale", "mara-glossy-sigma-scale", "px", {0, 64},
         "stages 9-10: sigma = scale x roughness^exponent + epsilon (the paper: 7)",
         BMFR_FIELD(S, glossySigmaScale)},
        {"glossySigmaExponent", "mara-glossy-sigma-exponent", "", {0, 10},
         "stages 9-10 roughness exponent (the paper: 0.1)", BMFR_FIELD(S, glossySigmaExponent)},
        {"glossySigmaEpsilon", "mara-glossy-sigma-epsilon", "px", {0, 1, true},
         "stages 9-10 epsilon (the paper does not say)", BMFR_FIELD(S, glossySigmaEpsilon)},
        {"glossyTapSigmas", "mara-glossy-tap-sigmas", "sigmas", {0, 10},
         "stages 9-10 taps reach ceil(this x sigma) pixels", BMFR_FIELD(S, glossyTapSigmas)},
        {"normalWeight", "mara-normal-weight", "", {0, 100},
         "bilateral k_n: weight max(0, 1 - k_n (1 - (n_c . n_q)^4))", BMFR_FIELD(S, normalWeight)},
        {"planeWeight", "mara-plane-weight", "", {0, 100},
         "bilateral k_p: weight max(0, 1 - 2 k_p |plane distance| / |dp|)^2",
         BMFR_FIELD(S, planeWeight)},
        {"planeNear", "mara-plane-near", "scene units", {0, 1e6},
         "bilateral: taps nearer than this keep full plane weight", BMFR_FIELD(S, planeNear)},
        {"seed", "mara-seed", "", {0, 4294967295.0}, "seed of the sparse taps' rotations",
         BMFR_FIELD(S, seed)},
    };
}
// clang-format on

} // namespace

const SettingsTable<Mara2017Settings>& mara2017SettingsTable() {
    static const SettingsTable<Mara2017Settings> table = withTemporalSettings(ownSettings());
    return table;
}

void validate(const Mara2017Settings& s) {
    checkSettings(mara2017SettingsTable(), s, "Mara 2017 setting");
    if (!(s.confidenceFar > s.confidenceNear))
        throw SettingError(
            "Mara 2017 setting confidenceFar (" + detail::formatNumber(s.confidenceFar) +
                ") must exceed confidenceNear (" + detail::formatNumber(s.confidenceNear) + ")",
            "confidenceFar", detail::formatNumber(s.confidenceFar),
            "must exceed confidenceNear (" + detail::formatNumber(s.confidenceNear) + ")");
}

} // namespace bmfr
