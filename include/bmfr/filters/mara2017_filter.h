// Mara, McGuire, Bitterli and Jarosz 2017, "An Efficient Denoising Algorithm for Global
// Illumination": the matte indirect light through a temporal filter with a world-space
// confidence, a sparse pre-bilateral on the history, a disocclusion radius, a firefly median and
// a final sparse bilateral; the glossy indirect light through a virtual-position temporal filter
// and a separable bilateral whose width follows roughness; then composed with the materials and
// the direct light. Reads FrameInput::matteIndirect and the other factorisation buffers; without
// them it filters the whole demodulated colour as matte. Ranges, units and defaults:
// `bmfr settings mara2017` or docs/settings.md.
#pragma once
#include <bmfr/device.h>
#include <bmfr/filter.h>
#include <bmfr/temporal_settings.h>
#include <cstdint>
#include <memory>

namespace bmfr {

/// Mara 2017 settings: the paper's constants where it gives them, the implementation notes'
/// defaults where it is silent. Distances are in scene units, the defaults in metres. The shared
/// `taa` is off by default (the paper has no TAA stage).
struct Mara2017Settings : TemporalSettings {
    Mara2017Settings() { taa = false; }
    float hysteresis = 0.98f;         ///< h: the largest weight of the history
    float confidenceNear = 0.05f;     ///< d0: reprojection distance where confidence starts to fall
    float confidenceFar = 0.07f;      ///< d1: reprojection distance where confidence reaches 0
    bool cumulativeStart = true;      ///< history weight min(c, n/(n+1)) for n frames of history
    bool clampHistory = true;         ///< clamp the history to the new samples' box min/max
    int clampRadius = 1;              ///< the clamp's box is (2 clampRadius + 1)^2 pixels
    bool preBilateral = true;         ///< stage 4: filter the history before it is stored
    int preTaps = 50;                 ///< stage 4 taps
    float preDiameter = 0.01f;        ///< stage 4 disk diameter, x screen width
    float preSigma = 0.5f;            ///< stage 4 Gaussian sigma, x disk radius
    float maxRadius = 0.05f;          ///< stage 5 R, x screen width
    float lowConfidence = 0.5f;       ///< stage 5: below this confidence the radius is boosted
    float radiusBoost = 6.0f;         ///< stage 5 boost of low-confidence pixels
    bool normaliseConfidence = false; ///< stage 5 reads c / h instead of c
    bool median = true;               ///< stage 6, the 3x3 firefly median
    int finalTaps = 50;               ///< stage 7 taps
    int rotationWidth = 16;           ///< stages 4 and 7: pixels along a row sharing a rotation
    float finalSigma = 0.5f;          ///< stage 7 Gaussian sigma, x radius r
    bool virtualReprojection = true;  ///< stage 8 reprojects the reflection's virtual position
    float glossySigmaScale = 7.0f;    ///< stages 9-10: sigma = scale * roughness^exponent + eps
    float glossySigmaExponent = 0.1f;
    float glossySigmaEpsilon = 1e-4f;
    float glossyTapSigmas = 3.0f; ///< stages 9-10 taps reach this many sigmas
    float normalWeight = 1.0f;    ///< bilateral k_n
    float planeWeight = 1.0f;     ///< bilateral k_p
    float planeNear = 0.0316f;    ///< bilateral: taps nearer than this keep full plane weight
    uint32_t seed = 0;            ///< seed of the sparse taps' rotations
};

/// Throws bmfr::Error naming the first setting out of range.
BMFR_API void validate(const Mara2017Settings& settings);

/// Named "mara2017" (Filter::name, makeFilter).
class BMFR_API Mara2017Denoiser final : public TemporalFilter {
  public:
    /// Throws bmfr::Error when a setting is out of range or the backend is not available.
    explicit Mara2017Denoiser(const Mara2017Settings& settings = {});
    /// On `device`, sharing its threads: settings.backend must be the device's, settings.threads
    /// is the device's.
    Mara2017Denoiser(const Mara2017Settings& settings, const Device& device);
};

} // namespace bmfr
