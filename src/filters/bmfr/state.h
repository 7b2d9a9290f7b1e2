// What every implementation of BMFR's passes shares: the frame timeline, the per-frame context
// and the interface an implementation (reference or fast CPU passes) offers the Denoiser.
#pragma once
#include "core/parallel.h"
#include <bmfr/denoiser.h>
#include <bmfr/frame.h>
#include <bmfr/settings.h>
#include <cstdint>
#include <memory>
#include <vector>

namespace bmfr {

/// Where the sequence stands: which history slot is current, the previous camera, the noise.
struct BmfrTimeline {
    int width = 0, height = 0;
    int cur = 0; ///< history slot written this frame; 1 - cur holds the previous frame
    bool hasHistory = false;
    Mat4 previousViewProjection;
    float previousJitter[2] = {0, 0};
    long frameIndex = 0;      ///< frames since construction: block offset and noise index
    std::vector<float> noise; ///< M x blockPixels regularisation noise of this frame
};

/// Inputs of one frame's passes.
struct BmfrPassContext {
    const Settings& settings;
    const FrameInput& frame;
    const BmfrTimeline& timeline;
    ThreadPool& pool;
};

/// What phase I counted while reading the inputs.
struct InputCounters {
    int64_t nonFinite = 0; ///< input values replaced by 0
    int64_t discarded = 0; ///< pixels whose whole history was discarded
};

/// One implementation of BMFR's per-frame passes over its own buffers.
class BmfrPasses {
  public:
    virtual ~BmfrPasses() = default;
    /// Sizes every buffer for w x h; called when the frame size changes.
    virtual void allocate(int w, int h, const Settings& s, int threads) = 0;
    /// Runs phase I to TAA for ctx.frame, writing the output to history slot timeline.cur and
    /// each stage's wall time to `times`.
    virtual InputCounters run(const BmfrPassContext& ctx, StageTimes& times) = 0;
    /// The final output of slot `slot` (3 channels, linear).
    virtual ImageView output(int slot) const = 0;
    /// Fills the debug buffers of the frame just run (called only when they are wanted).
    virtual void captureDebug(const BmfrTimeline& t) = 0;
    virtual DebugBuffers debug(const BmfrTimeline& t) const = 0;
};

/// The straightforward passes, one per stage (src/backend/reference).
std::unique_ptr<BmfrPasses> makeReferencePasses();
/// The fast CPU passes: SIMD, block-streamed fitting, phase III fused with TAA (src/backend/cpu).
std::unique_ptr<BmfrPasses> makeFastPasses();

} // namespace bmfr
