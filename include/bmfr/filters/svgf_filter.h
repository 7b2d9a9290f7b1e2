// Spatiotemporal Variance-Guided Filtering (Schied et al. 2017), with the progressive variant of
// Dundr's thesis as settings. Ranges, units and defaults: `bmfr settings svgf` or docs/settings.md.
#pragma once
#include <bmfr/device.h>
#include <bmfr/filter.h>
#include <bmfr/temporal_settings.h>
#include <memory>

namespace bmfr {

/// SVGF settings; defaults are Schied et al. 2017's.
struct SvgfSettings : TemporalSettings {
    float colorAlpha = 0.2f;   ///< colour accumulation minimum new-frame weight
    float momentsAlpha = 0.2f; ///< luminance moments minimum new-frame weight
    int iterations = 5;        ///< a-trous levels (steps 1, 2, 4, ... pixels)
    int kernelRadius = 2;      ///< 2 = 5x5 B3 spline (Schied), 1 = 3x3 (progressive)
    /// Coarse-to-fine level order (progressive). The level fed back as the next frame's colour
    /// history is always the step-1 level.
    bool reverseLevels = false;
    float phiDepth = 1.0f;         ///< depth edge stopping sigma_z
    float phiNormal = 128.0f;      ///< normal edge-stopping exponent sigma_n
    float phiLuminance = 4.0f;     ///< luminance edge stopping sigma_l
    int spatialVarianceFrames = 4; ///< spatial variance estimate below this history length
};

/// Throws bmfr::Error naming the first setting out of range.
BMFR_API void validate(const SvgfSettings& settings);

/// Named "svgf" (Filter::name, makeFilter).
class BMFR_API SvgfDenoiser final : public TemporalFilter {
  public:
    /// Throws bmfr::Error when a setting is out of range or the backend is not available.
    explicit SvgfDenoiser(const SvgfSettings& settings = {});
    /// On `device`, sharing its threads: settings.backend must be the device's, settings.threads
    /// is the device's.
    SvgfDenoiser(const SvgfSettings& settings, const Device& device);
    /// The variance estimate of the last frame before the a-trous filter (1 channel).
    ImageView variance() const;
};

} // namespace bmfr
