#include "filters/bmfr/bmfr_settings_table.h"
#include "temporal/temporal_settings_table.h"

namespace bmfr {

namespace {

using S = BmfrSettings;

TextField<S> featuresField() {
    return {+[](const S& s) { return formatFeatures(s.features); },
            +[](S& s, const std::string& v) { s.features = parseFeatures(v); }};
}

// The defaults are the quality preset's: the paper's, with the switches and values that
// measured better than the paper on our sequences (docs/presets.md). The last value of a row,
// where there is one, is the faithful preset's (the paper's). Half the paper's block:
// multi-bounce light in Sponza varies faster than a 32-pixel block's polynomial follows, at
// 320x180 and at 640x360 alike; the emitter mask then needs the lower ratio, as a lamp's smeared
// edge is a larger share of a smaller block. Half the paper's regularisation noise shrinks the
// fit less towards its mean (the rooms' error 2% to 4.5% lower against 1024-spp references);
// phase III's floor weight goes from 0.1 to 0.08 and averages the less regularised fits over
// more frames (still-camera flicker 3% to 4% lower than with the paper's two values).
// clang-format off
SettingsTable<S> ownSettings() {
    return {
        {"blockSize", "block-size", "pixels", {8, 64}, "edge of the square regression block (even)",
         BMFR_FIELD(S, blockSize), "32"},
        {"features", "features", "", {},
         "columns of T (paper eq. 8): 1, n.x, n.y, n.z, p.x, p.y, p.z, extraK "
         "(FrameInput::extras[K]), each optionally ^E; the constant 1 first, at most 24",
         featuresField()},
        {"noiseAmplitude", "noise", "", {0, 1},
         "half-width of the uniform regularisation noise added to every non-constant scaled "
         "feature column, never to colour",
         BMFR_FIELD(S, noiseAmplitude), "0.01"},
        {"firstBlendAlpha", "alpha1", "", {0, 1, true},
         "phase I minimum new-frame weight (cumulative average until 1/(n+1) drops below it)",
         BMFR_FIELD(S, firstBlendAlpha)},
        {"secondBlendAlpha", "alpha2", "", {0, 1, true},
         "phase III minimum new-frame weight, max(1/n, alpha2)", BMFR_FIELD(S, secondBlendAlpha), "0.1"},
        {"seed", "seed", "", {0, 4294967295.0},
         "regularisation noise seed; the same seed and input give the same bits at any thread "
         "count",
         BMFR_FIELD(S, seed)},
        {"halfHistory", "half-history", "", {},
         "store normals, colour history and history length as 16-bit floats (the paper's "
         "choice; saturated at 65504): a fifth fewer bytes per frame and 30% less history "
         "memory, tone-mapped RMSE within 0.5% of float32's; false gives float32 history for "
         "bit-exact work. Positions stay float32",
         BMFR_FIELD(S, halfHistory)},
        {"excludeEmitters", "exclude-emitters", "", {},
         "leave out of each block's fit the pixels far above its lower-quartile luminance "
         "(emitterRatio) around a flat, bright patch of current samples, as a light in view "
         "without an emission buffer: the light keeps its own sample, and no history crosses "
         "its edge. Does nothing with an emission buffer",
         BMFR_FIELD(S, excludeEmitters), "false"},
        {"clampFireflies", "clamp-fireflies", "", {},
         "in the fit's input (not the history), a pixel above 8x its block's median luminance "
         "with at most three such neighbours is scaled down to that level, so a firefly does "
         "not brighten its block; in full without history, fading to nothing at 5 samples of "
         "history (unbiased where the history is long), except within 2 pixels of a light of "
         "the previous frame, whose smeared history it keeps out of the fit",
         BMFR_FIELD(S, clampFireflies), "false"},
        {"secondGrid", "second-grid", "", {},
         "pixels without history (the first frame after a reset, disocclusions) take the mean of "
         "the fit and a second fit on the grid moved by half a block, so the block edges blur "
         "out",
         BMFR_FIELD(S, secondGrid), "false"},
        {"visibilityFeature", "visibility-feature", "", {},
         "when frames carry a visibility buffer (the key light's noise-free shadow times its "
         "cosine), fit it as one more feature column, so a hard shadow edge does not block up; "
         "give it on every frame or none",
         BMFR_FIELD(S, visibilityFeature), "false"},
        {"visibilityTaps", "visibility-taps", "", {},
         "when frames carry a visibility buffer, phases I and III and the same-surface TAA take "
         "no history tap whose pixel was lit (visibility above 0) last frame where this one is "
         "not, or the reverse, so shadow edges stay sharp; give it on every frame or none",
         BMFR_FIELD(S, visibilityTaps), "false"},
        {"adaptiveHistory", "adaptive-history", "", {},
         "where a 32x32 tile's mean current sample has left its reprojected history's mean by "
         "more than historyChangeThreshold standard errors (a moving light), phase III weighs "
         "the new frame more, in proportion, and both phases' histories shorten; elsewhere they "
         "stay the paper's",
         BMFR_FIELD(S, adaptiveHistory), "false"},
        {"historyChangeThreshold", "history-change-threshold", "standard errors", {0, 100},
         "adaptiveHistory: how far a tile's mean current sample may lie from its history's mean "
         "before the history counts as stale, in standard errors of that mean",
         BMFR_FIELD(S, historyChangeThreshold)},
        {"historyChangeGain", "history-change-gain", "ratio", {0, 1000},
         "adaptiveHistory: a tile's change (its means' gap beyond the noise, as a fraction of "
         "the larger) is multiplied by this before it raises the weights, capped at 1; 1 is "
         "A-SVGF's, 4 measured best on a moving light at no cost from a still camera",
         BMFR_FIELD(S, historyChangeGain)},
        {"emitterRatio", "emitter-ratio", "ratio", {2, 1e6},
         "excludeEmitters: the demodulated accumulated luminance, as a multiple of the block's "
         "lower quartile, above which a pixel may belong to an emitter",
         BMFR_FIELD(S, emitterRatio), "16"},
        {"demodulate", "demodulate", "", {}, "divide colour by albedo before filtering",
         BMFR_FIELD(S, stages.demodulate)},
        {"firstAccumulation", "accumulation", "", {}, "phase I: accumulate the noisy colour",
         BMFR_FIELD(S, stages.firstAccumulation)},
        {"fitting", "fitting", "", {}, "phase II: blockwise feature regression",
         BMFR_FIELD(S, stages.fitting)},
        {"secondAccumulation", "second-accumulation", "", {},
         "phase III: accumulate the fitted colour", BMFR_FIELD(S, stages.secondAccumulation)},
    };
}
// clang-format on

} // namespace

const SettingsTable<BmfrSettings>& bmfrSettingsTable() {
    static const SettingsTable<BmfrSettings> table = withTemporalSettings(ownSettings());
    return table;
}

void validate(const BmfrSettings& s) {
    checkSettings(bmfrSettingsTable(), s, "setting");
    if (s.blockSize % 2 != 0)
        throw SettingError("setting blockSize = " + std::to_string(s.blockSize) + " must be even",
                           "blockSize", std::to_string(s.blockSize), "must be even");
    auto featuresError = [&](const std::string& problem) {
        const std::string value = formatFeatures(s.features);
        return SettingError("setting features " + value + " " + problem, "features", value,
                            problem);
    };
    if (s.features.empty() || s.features.front().source != FeatureSource::One)
        throw featuresError("must begin with the constant 1");
    // Room for the visibility column too, so that turning it on never fails later.
    const int columns = int(s.features.size()) + (s.visibilityFeature ? 1 : 0);
    if (columns > kMaxFeatures)
        throw featuresError("is " + std::to_string(s.features.size()) + " features" +
                            (s.visibilityFeature ? " and the visibility" : "") + ", more than " +
                            std::to_string(kMaxFeatures) + " columns");
    if (columns + 3 > s.blockSize * s.blockSize)
        throw featuresError("is more features than pixels in a block");
}

} // namespace bmfr
