// The shared settings' rows of every filter's settings table (TemporalSettings): each filter's
// table starts with these.
#pragma once
#include "core/settings_table.h"
#include <bmfr/temporal_settings.h>

namespace bmfr {

template <class S> TextField<S> backendField() {
    return {+[](const S& s) { return std::string(backendName(s.backend)); },
            +[](S& s, const std::string& v) { s.backend = parseBackend(v.c_str()); }};
}

// clang-format off
template <class S> SettingsTable<S> temporalSettingsTable() {
    return {
        {"backend", "backend", "", {}, "where the passes run: reference, cpu or cuda",
         backendField<S>()},
        {"positionLimitSquared", "position-limit", "scene units^2", {0, 1e30, true},
         "discard a history tap when its squared world distance is at least this (a sequence's "
         "own value, when it has one, replaces the default)",
         BMFR_FIELD(S, positionLimitSquared)},
        {"normalLimitSquared", "normal-limit", "", {0, 4, true},
         "discard a history tap when its squared normal distance is at least this (1 is about "
         "60 degrees; a sequence's own value replaces the default)",
         BMFR_FIELD(S, normalLimitSquared)},
        {"taaBlendAlpha", "taa-alpha", "", {0, 1, true}, "TAA weight of the current frame",
         BMFR_FIELD(S, taaBlendAlpha)},
        {"taa", "taa", "", {}, "temporal anti-aliasing of the output", BMFR_FIELD(S, taa)},
        {"taaSameSurface", "taa-same-surface", "", {},
         "TAA takes the history only from the bilinear taps that passed the history discard "
         "test (the same surface), so edges do not blur under motion; false: all four taps, "
         "the authors'",
         BMFR_FIELD(S, taaSameSurface), "false"},
        {"taaToneMapped", "taa-tone-mapped", "", {},
         "TAA blends display values clamp(x^(1/2.2), 0, 1), as the authors' code does on its "
         "tone-mapped frame, and converts the result back to linear (x^2.2): values above 1 come "
         "out as 1. False: TAA on linear radiance",
         BMFR_FIELD(S, taaToneMapped)},
        {"taaRangeCompressed", "taa-range-compressed", "", {},
         "TAA blends range-compressed radiance c / (1 + max(r, g, b)) and expands the result "
         "back (Karis 2014), so that a light's pixel weighs in its neighbours' history as a "
         "display shows it, not by its radiance; nothing is clipped. taaToneMapped, when set, "
         "replaces it. False: linear radiance, the authors' order of operations",
         BMFR_FIELD(S, taaRangeCompressed), "false"},
        {"taaMotionWeight", "taa-motion-weight", "", {},
         "TAA weighs the current frame more where the history is resampled between pixels "
         "(under motion, or jitter; fractions within 1/32 px of a pixel count as none), so that "
         "the blur repeated resampling gathers stays within "
         "taaBlurLimit: the weight is max(taaBlendAlpha, b / (b + taaBlurLimit)) for the blur "
         "b = ax (1 - ax) + ay (1 - ay) of the bilinear fractions ax, ay. A still camera "
         "without jitter keeps taaBlendAlpha; false: taaBlendAlpha everywhere, the authors'",
         BMFR_FIELD(S, taaMotionWeight), "false"},
        {"taaBlurLimit", "taa-blur-limit", "px^2", {1e-4, 100},
         "taaMotionWeight: the blur, as a variance, that the TAA history may gather from its "
         "resamplings",
         BMFR_FIELD(S, taaBlurLimit)},
        {"albedoEpsilon", "albedo-epsilon", "", {1e-6, 1},
         "demodulation divides by max(albedo, eps) and re-modulation multiplies by the same",
         BMFR_FIELD(S, albedoEpsilon)},
        {"colorIsDemodulated", "color-is-demodulated", "", {},
         "the colour input is already divided by albedo (the original BMFR dataset is)",
         BMFR_FIELD(S, colorIsDemodulated)},
        {"threads", "threads", "threads", {0, 1024}, "worker threads, 0 = all cores",
         BMFR_FIELD(S, threads)},
    };
}
// clang-format on

/// The shared rows followed by a filter's own.
template <class S> SettingsTable<S> withTemporalSettings(const SettingsTable<S>& own) {
    SettingsTable<S> t = temporalSettingsTable<S>();
    t.insert(t.end(), own.begin(), own.end());
    return t;
}

/// How many rows of every filter's table are the shared ones.
inline int temporalSettingCount() {
    return int(temporalSettingsTable<TemporalSettings>().size());
}

} // namespace bmfr
