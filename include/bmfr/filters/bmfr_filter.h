// BMFR, Blockwise Multi-Order Feature Regression (Koskela et al., ACM TOG 2019): its settings
// and its denoiser. Ranges, units and defaults: `bmfr settings bmfr` or docs/settings.md.
#pragma once
#include <bmfr/device.h>
#include <bmfr/features.h>
#include <bmfr/filter.h>
#include <bmfr/temporal_settings.h>
#include <cstdint>
#include <memory>
#include <vector>

namespace bmfr {

/// Stage switches, for ablations. A disabled stage passes its input through unchanged; TAA is
/// the shared TemporalSettings::taa.
struct StageSwitches {
    bool demodulate = true;         ///< divide colour by albedo before filtering, re-multiply after
    bool firstAccumulation = true;  ///< phase I: temporal accumulation of the noisy colour
    bool fitting = true;            ///< phase II: blockwise feature regression
    bool secondAccumulation = true; ///< phase III: temporal accumulation of the fitted colour
};

/// BMFR settings. The defaults are the quality preset: the paper's and the authors' code, with the
/// improvements beyond them that measured better (docs/presets.md); presetSettings("bmfr",
/// "faithful") sets the paper's back.
struct BmfrSettings : TemporalSettings {
    int blockSize = 16;                                ///< edge of the square regression block
    std::vector<Feature> features = defaultFeatures(); ///< columns of T; the constant 1 first
    float noiseAmplitude = 0.005f;  ///< half-width of the regularisation noise on feature columns
    float firstBlendAlpha = 0.2f;   ///< phase I minimum new-frame weight (CMA, then EMA)
    float secondBlendAlpha = 0.08f; ///< phase III minimum new-frame weight
    uint32_t seed = 0;              ///< regularisation noise seed
    bool halfHistory = true;        ///< normals and colour history as 16-bit floats (else float32)
    bool excludeEmitters = true;    ///< fit blocks without bright patches (lights in view)
    float emitterRatio = 4.0f;      ///< a patch pixel is this many times the block's median
    bool secondGrid = true;         ///< pixels without history also fitted on a shifted grid
    bool clampFireflies = true;     ///< isolated pixels far above their block clamped in the fit
    bool visibilityFeature = true;  ///< fit FrameInput::visibility as one more feature, if given
    bool visibilityTaps = true;  ///< no phase III / TAA history across FrameInput::visibility edges
    bool adaptiveHistory = true; ///< shorter histories where the lighting changed
    float historyChangeThreshold = 2.0f; ///< adaptiveHistory: the noise allowance, standard errors
    float historyChangeGain = 4.0f;      ///< adaptiveHistory: how strongly a change shortens them
    StageSwitches stages{};
};

/// Throws bmfr::Error naming the first setting out of its range.
BMFR_API void validate(const BmfrSettings& settings);

/// The authors' 16 block-grid offsets in pixels, used in order, one per frame.
inline constexpr int kBlockOffsets[16][2] = {
    {-14, -14}, {4, -6},   {-8, 14}, {8, 0},   {-10, -8}, {2, 12},   {12, -12}, {-10, 0},
    {12, 14},   {-8, -16}, {6, 6},   {-2, -2}, {6, -14},  {-16, 12}, {14, -4},  {-6, 4}};

/// Temporal BMFR reconstruction. Not thread-safe; one instance per sequence.
/// Named "bmfr" (Filter::name, makeFilter).
class BMFR_API BmfrDenoiser final : public TemporalFilter {
  public:
    /// Throws bmfr::Error when a setting is out of range or the backend is not available.
    explicit BmfrDenoiser(const BmfrSettings& settings = {});
    /// On `device`, sharing its threads: settings.backend must be the device's, settings.threads
    /// is the device's.
    BmfrDenoiser(const BmfrSettings& settings, const Device& device);
    const BmfrSettings& settings() const;
};

/// Earlier names, kept for a while.
using Settings = BmfrSettings;
using Denoiser = BmfrDenoiser;

} // namespace bmfr
