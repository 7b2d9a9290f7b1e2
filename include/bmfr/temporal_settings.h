// The settings every temporal filter shares (BMFR and SVGF): the reprojection discard test,
// TAA, demodulation and threads. Each filter's settings struct derives from it.
#pragma once

namespace bmfr {

struct TemporalSettings {
    /// A history tap is discarded when |p_prev - p|^2 >= this; scene units squared; > 0;
    /// default 0.01 (the authors' dataset value).
    float positionLimitSquared = 0.01f;
    /// A history tap is discarded when |n_prev - n|^2 >= this; unitless; (0, 4]; default 1.0
    /// (about 60 degrees).
    float normalLimitSquared = 1.0f;
    /// Weight of the current frame in TAA; (0, 1]; default 0.2.
    float taaBlendAlpha = 0.2f;
    /// Albedo channels below this are treated as this when demodulating; [1e-6, 1]; 0.001.
    float albedoEpsilon = 0.001f;
    /// The colour input is already divided by albedo (the original BMFR dataset is).
    bool colorIsDemodulated = false;
    /// Worker threads; 0 = all cores; [0, 1024].
    int threads = 0;
};

/// Throws bmfr::Error naming the first shared setting out of its range; `filter` prefixes the
/// message ("setting" for BMFR, "SVGF setting").
void validate(const TemporalSettings& settings, const char* filter);

} // namespace bmfr
