// Every setting of the BMFR filter, each with its unit, range and default.
#pragma once
#include <bmfr/features.h>
#include <bmfr/temporal_settings.h>
#include <cstdint>
#include <vector>

namespace bmfr {

/// Stage switches, for ablations. A disabled stage passes its input through unchanged.
struct StageSwitches {
    bool demodulate = true;         ///< divide colour by albedo before filtering, re-multiply after
    bool firstAccumulation = true;  ///< phase I: temporal accumulation of the noisy colour
    bool fitting = true;            ///< phase II: blockwise feature regression
    bool secondAccumulation = true; ///< phase III: temporal accumulation of the fitted colour
    bool taa = true;                ///< phase III: temporal anti-aliasing
};

/// Which CPU passes run. Both give the same output within rounding (tests hold them to 1e-3).
enum class Implementation {
    Fast,     ///< SIMD, block-streamed fitting, phase III fused with TAA (default)
    Reference ///< one straightforward pass per stage: the specification of the fast passes
};

/// BMFR settings. Defaults are the paper's (Koskela et al. 2019) and the authors' code. The
/// shared ones (discard limits, TAA weight, albedo floor, threads) are in TemporalSettings.
struct Settings : TemporalSettings {
    /// Edge of the square regression block, pixels; [8, 64]; default 32.
    int blockSize = 32;
    /// Columns of the regression matrix T; first must be the constant 1; at most kMaxFeatures.
    std::vector<Feature> features = defaultFeatures();
    /// Half-width eps of the uniform regularisation noise U[-eps, eps] added to every
    /// non-constant scaled feature column (never to colour); unitless; [0, 1]; default 0.01.
    float noiseAmplitude = 0.01f;
    /// Minimum weight of the new frame in phase I (CMA until 1/(n+1) drops below it, then EMA);
    /// unitless; (0, 1]; default 0.2.
    float firstBlendAlpha = 0.2f;
    /// Minimum weight of the new fitted frame in phase III, weight max(1/n, alpha); (0, 1]; 0.1.
    float secondBlendAlpha = 0.1f;
    /// Seed of the regularisation noise; same seed and input give the same output bits.
    uint32_t seed = 0;
    /// Ablation switches.
    StageSwitches stages{};
    /// Fast (default) or Reference passes.
    Implementation implementation = Implementation::Fast;
};

/// Throws bmfr::Error naming the first setting out of its range.
void validate(const Settings& settings);

/// The authors' 16 block-grid offsets in pixels, used in order, one per frame.
inline constexpr int kBlockOffsets[16][2] = {
    {-14, -14}, {4, -6},   {-8, 14}, {8, 0},   {-10, -8}, {2, 12},   {12, -12}, {-10, 0},
    {12, 14},   {-8, -16}, {6, 6},   {-2, -2}, {6, -14},  {-16, 12}, {14, -4},  {-6, 4}};

} // namespace bmfr
