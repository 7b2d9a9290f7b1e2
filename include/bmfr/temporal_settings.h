// The settings every temporal filter shares (BMFR, SVGF and those to come): the backend, the
// reprojection discard test, TAA, demodulation and threads. Each filter's settings derive from it.
// Ranges and defaults are stated once, in the settings table (src/temporal/temporal_settings.cpp),
// which validation, the command line and docs/settings.md's table are made from.
#pragma once
#include <bmfr/api.h>
#include <string>
#include <vector>

namespace bmfr {

/// Where a filter's passes run. Every backend gives the reference backend's output within the
/// conformance suite's tolerance, with identical discard decisions and history lengths.
enum class Backend {
    Reference, ///< one readable scalar pass per stage: the specification
    Cpu,       ///< threads and SIMD, passes fused (default)
    Cuda       ///< NVIDIA GPUs, where the build found CUDA (else choosing it is an error)
};

struct TemporalSettings {
    Backend backend = Backend::Cpu;     ///< where the passes run
    float positionLimitSquared = 0.01f; ///< history discard: squared world distance, units^2
    float normalLimitSquared = 1.0f;    ///< history discard: squared normal distance
    float taaBlendAlpha = 0.2f;         ///< TAA weight of the current frame
    bool taa = true;                    ///< temporal anti-aliasing on the output
    bool taaSameSurface = true;         ///< TAA history only from taps on the same surface
    bool taaToneMapped = false;         ///< TAA on display values, as the authors' (clips at 1)
    bool taaRangeCompressed = true;     ///< TAA on c / (1 + max(c)), so lights do not bleed
    bool taaMotionWeight = true;        ///< TAA weighs the current frame more under motion
    float taaBlurLimit = 0.005f;        ///< taaMotionWeight: blur the history may gather, px^2
    float albedoEpsilon = 0.001f;       ///< albedo floor when (de)modulating
    bool colorIsDemodulated = false;    ///< the colour input is already divided by albedo
    int threads = 0;                    ///< worker threads, 0 = all cores
};

/// Throws bmfr::Error naming the first shared setting out of its range.
BMFR_API void validate(const TemporalSettings& settings);

/// "reference", "cpu" or "cuda"; parseBackend throws bmfr::Error for other names.
BMFR_API const char* backendName(Backend backend);
BMFR_API Backend parseBackend(const char* name);
/// The backends this build of the library holds, by name ("cuda" only where it was built).
BMFR_API std::vector<std::string> compiledBackends();

} // namespace bmfr
