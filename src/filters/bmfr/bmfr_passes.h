// The interface a backend implements for BMFR (reference, cpu, ...), and what every
// implementation shares: the frame timeline and the per-frame context.
#pragma once
#include "core/parallel.h"
#include "temporal/history.h"
#include "temporal/pixel_input.h"
#include <bmfr/filters/bmfr_filter.h>
#include <cstdint>
#include <memory>
#include <vector>

namespace bmfr {

/// Where the sequence stands: the shared history bookkeeping and this frame's noise.
struct BmfrTimeline {
    TemporalHistory history;
    std::vector<float> noise; ///< M x blockPixels regularisation noise of this frame
};

/// Inputs of one frame's passes.
struct BmfrPassContext {
    const BmfrSettings& settings;
    const InputPlanes& input;
    const FrameInput& frame; ///< the caller's buffers (device ones are staged by the backend)
    const BmfrTimeline& timeline;
    ThreadPool& pool;
};

/// What phase I counted while reading the inputs.
struct InputCounters {
    int64_t nonFinite = 0; ///< input values replaced by 0
    int64_t discarded = 0; ///< pixels whose whole history was discarded
};

/// One backend's BMFR passes over its own buffers.
class BmfrPasses {
  public:
    virtual ~BmfrPasses() = default;
    /// False when the backend draws the regularisation noise itself (on its device).
    virtual bool needsHostNoise() const { return true; }
    /// Sizes every buffer for w x h; called when the frame size changes.
    virtual void allocate(int w, int h, const BmfrSettings& s, int threads) = 0;
    /// Runs phase I to TAA, writing the output to history slot timeline.history.cur and each
    /// stage's wall time to `times`.
    virtual InputCounters run(const BmfrPassContext& ctx, StageTimes& times) = 0;
    /// The final output of slot `slot` (3 channels, linear).
    virtual ImageView output(int slot) const = 0;
    /// Fills the debug buffers of the frame just run (called only when they are wanted).
    virtual void captureDebug(const BmfrTimeline& t) = 0;
    virtual DebugBuffers debug(const BmfrTimeline& t) const = 0;
};

} // namespace bmfr
