// WALR, Weighted A-Trous Linear Regression (Meunier and Harada 2022): BMFR's pipeline with the
// blockwise fit replaced by a per-pixel weighted regression on edge-traced a-trous averages, and
// REFWLR, the paper's direct reference solver. Ranges, units and defaults: `bmfr settings walr`
// or docs/settings.md.
#pragma once
#include <bmfr/device.h>
#include <bmfr/filter.h>
#include <bmfr/temporal_settings.h>
#include <cstdint>
#include <memory>

namespace bmfr {

/// What WALR filters.
enum class WalrSignal {
    Color,          ///< the whole demodulated colour, exactly what BMFR filters
    DiffuseIndirect ///< FrameInput::diffuseIndirect only (the paper); the rest added unfiltered
};

/// The spatial solver.
enum class WalrSolver {
    Walr,  ///< edge-traced a-trous averages and a per-pixel 3x3 Cholesky (the paper's filter)
    Refwlr ///< a direct weighted regression over the whole 3^T window (the paper's oracle; slow)
};

/// How the preprocess decides whether a pixel's history is the same surface.
enum class WalrHistoryTest {
    Depth, ///< the paper: expected previous view depth against the history's depth
    World  ///< the shared world position and normal limits (BMFR's test, at the nearest pixel)
};

/// WALR settings; defaults follow the paper and, where it is silent, the implementation notes.
/// The shared taaBlendAlpha is the postprocess's minimum new-frame weight (0.1 by default) and
/// the shared taa switches the postprocess.
struct WalrSettings : TemporalSettings {
    WalrSettings() { taaBlendAlpha = 0.1f; }
    WalrSignal signal = WalrSignal::Color; ///< what is filtered
    WalrSolver solver = WalrSolver::Walr;  ///< the spatial solver
    int iterations = 0; ///< a-trous iterations T (tap spacing 3^t, window 3^T); 0 = by image size
    bool edgeTracing = true;        ///< test every pixel on a tap's segment, not only its end
    bool averageReplacement = true; ///< a discarded tap takes an average before the edge
    float edgeStep = 0.0f;          ///< stepped tracing: share of a flat run skipped; 0 = exact
    bool sampleWeights = false;     ///< keep the sample-count weights W (the paper drops them)
    float edgeNear = 0.005f;        ///< plane distance where the weight starts to fall, x depth
    float edgeFar = 0.02f;          ///< plane distance where the weight reaches 0, x depth
    float pivotEpsilon = 1e-4f;     ///< Cholesky pivot floor of the two normal features
    bool halfAverages = true;       ///< averages pass between iterations as halves (the paper's)
    float preAlpha = 0.2f;          ///< preprocess minimum new-frame weight
    float depthTolerance = 0.02f;   ///< depth test: relative view-depth difference
    WalrHistoryTest historyTest = WalrHistoryTest::Depth; ///< the preprocess's history test
    bool motionDilation = true; ///< take the motion of the nearest pixel in the 3x3
    float varianceGamma = 1.0f; ///< postprocess clip box: mean +- gamma standard deviations
    uint32_t seed = 0;          ///< the hashed choices of average replacement
};

/// Throws bmfr::Error naming the first setting out of range.
BMFR_API void validate(const WalrSettings& settings);

/// The iterations T used for a width x height frame: settings.iterations, or when it is 0 the
/// T whose 3^T window is nearest the share of the frame that the paper's 80x80 is of a
/// 1080-pixel frame, by the shorter side: 5 from 1896 pixels, 4 from 632 (720p, 1080p), 3 from
/// 211 (240p to 480p), 2 from 71, else 1.
BMFR_API int walrIterations(const WalrSettings& settings, int width, int height);

/// Named "walr" (Filter::name, makeFilter).
class BMFR_API WalrDenoiser final : public TemporalFilter {
  public:
    /// Throws bmfr::Error when a setting is out of range or the backend is not available.
    explicit WalrDenoiser(const WalrSettings& settings = {});
    /// On `device`, sharing its threads: settings.backend must be the device's, settings.threads
    /// is the device's.
    WalrDenoiser(const WalrSettings& settings, const Device& device);
};

} // namespace bmfr
