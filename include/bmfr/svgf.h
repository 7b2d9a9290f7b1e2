// Spatiotemporal Variance-Guided Filtering (Schied et al. 2017), with the progressive variant of
// Dundr's thesis as settings; behind the same Filter interface as BMFR.
#pragma once
#include <bmfr/filter.h>
#include <bmfr/temporal_settings.h>
#include <cstdint>

namespace bmfr {

/// SVGF settings; defaults are Schied et al. 2017's. The shared ones (discard limits, TAA
/// weight, albedo floor, threads) are in TemporalSettings.
struct SvgfSettings : TemporalSettings {
    /// Minimum new-frame weight of the colour accumulation (cumulative average before it),
    /// unitless; (0, 1]; default 0.2.
    float colorAlpha = 0.2f;
    /// The same for the luminance moments; (0, 1]; default 0.2.
    float momentsAlpha = 0.2f;
    /// A-trous levels; [1, 8]; default 5 (steps 1, 2, 4, 8, 16 pixels).
    int iterations = 5;
    /// Kernel radius in taps: 2 = 5x5 B3 spline (Schied), 1 = 3x3 (progressive variant); [1, 2].
    int kernelRadius = 2;
    /// Coarse-to-fine level order (progressive variant). The level fed back as the next frame's
    /// colour history is always the step-1 level: the first in the original order, the last
    /// when reversed.
    bool reverseLevels = false;
    /// Depth edge stopping sigma_z, unitless; > 0; default 1.
    float phiDepth = 1.0f;
    /// Normal edge-stopping exponent sigma_n: weight max(0, n0.n1)^sigma_n; [1, 1024]; default 128.
    float phiNormal = 128.0f;
    /// Luminance edge stopping sigma_l: weight exp(-|l0-l1| / (sigma_l sqrt(var) + eps)); > 0; 4.
    float phiLuminance = 4.0f;
    /// Spatial 7x7 variance estimate while the history is shorter than this many frames;
    /// [0, 255]; default 4; 0 disables it (progressive variant).
    int spatialVarianceFrames = 4;
    /// TAA on or off.
    bool taa = true;
};

/// Throws bmfr::Error naming the first setting out of range.
void validate(const SvgfSettings& settings);

class SvgfDenoiser final : public Filter {
  public:
    explicit SvgfDenoiser(const SvgfSettings& settings = {});
    ~SvgfDenoiser() override;
    ImageView denoise(const FrameInput& frame) override;
    void reset() override;
    const FrameStats& lastStats() const override;
    const char* name() const override { return "svgf"; }
    /// The variance estimate of the last frame before the a-trous filter (1 channel).
    ImageView variance() const;

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace bmfr
