// The interface every backend implements for every filter: staging the caller's frame, one
// frame's passes over the backend's own buffers, and writing the result into a caller's view.
#pragma once
#include "core/executor.h"
#include "core/parallel.h"
#include "temporal/history.h"
#include "temporal/input_staging.h"
#include "temporal/pixel_input.h"
#include <bmfr/filter.h>
#include <cstdint>

namespace bmfr {

/// Inputs of one frame's passes, for a filter with settings S.
template <class S> struct PassContext {
    const S& settings;
    const InputPlanes& input;
    const FrameInput& frame; ///< the caller's buffers (device ones are staged by the backend)
    const TemporalHistory& history;
    ThreadPool& pool;
};

/// What the passes counted in one frame (FrameStats's fields of the same names).
struct PassCounters {
    int64_t nonFinite = 0; ///< input values replaced by 0
    int64_t discarded = 0; ///< pixels that had a history and kept no tap of it
};

/// Pixels of an accept mask (bit i = bilinear tap i) that kept no tap, when there was a history.
int64_t countDiscarded(ThreadPool& pool, const uint8_t* accept, long pixels, bool hasHistory);
/// countDiscarded on an executor, added to `discarded` (a device backend's count).
template <class Exec>
void countDiscarded(const Exec& e, const uint8_t* accept, long pixels, bool hasHistory,
                    FrameCounter discarded) {
    if (hasHistory)
        e.forEachIndex(
            pixels, BMFR_LAMBDA(long i) { discarded.add(accept[i] == 0 ? 1 : 0); });
}

/// How a backend reads the caller's frame and writes into the caller's view. The host
/// backends stage into host planes; a device backend overrides all three.
class FrameTransfer {
  public:
    virtual ~FrameTransfer() = default;
    /// True when the passes read frames in CUDA device memory.
    virtual bool readsDeviceMemory() const { return false; }
    /// The frame's planes, valid until the next call; the frame passed checkFrameInput.
    virtual const InputPlanes& stage(const FrameInput& frame) { return staging_.stage(frame); }
    /// Writes `result` (an output(slot) of these passes) into `out`, ordered on `cudaStream`.
    virtual void write(const ImageView& result, const MutableImageView& out, void* cudaStream) {
        (void)cudaStream;
        writeOutput(result, out);
    }

  private:
    InputStaging staging_;
};

/// One backend's passes of the filter with settings S.
template <class S> class FilterPasses : public FrameTransfer {
  public:
    /// Sizes every buffer for w x h with these settings; called when the size or the settings'
    /// columns change.
    virtual void allocate(int w, int h, const S& settings, int threads) = 0;
    /// Runs every stage, writing the output to history slot ctx.history.cur and each stage's
    /// wall time to `times`.
    virtual PassCounters run(const PassContext<S>& ctx, StageTimes& times) = 0;
    /// The final output of slot `slot` (3 channels, linear).
    virtual ImageView output(int slot) const = 0;
    /// Fills the debug buffers of the frame just run (called only when they are wanted).
    virtual void captureDebug(const TemporalHistory& history) = 0;
    virtual DebugBuffers debug(const TemporalHistory& history) const = 0;
};

/// The passes interface of the filter with settings S: FilterPasses<S>, or a filter's own
/// extension of it where the filter offers more (SVGF's variance).
template <class S> struct PassesOf { using type = FilterPasses<S>; };
template <class S> using PassesFor = typename PassesOf<S>::type;

/// The part of a host backend's passes that only reads its buffers B: B::allocate(w, h),
/// B::result(slot), B::captureDebug(cur) and B::debug(cur).
template <class S, class B> class HostPasses : public PassesFor<S> {
  public:
    void allocate(int w, int h, const S&, int) override { buffers.allocate(w, h); }
    ImageView output(int slot) const override { return buffers.result(slot); }
    void captureDebug(const TemporalHistory& h) override { buffers.captureDebug(h.cur); }
    DebugBuffers debug(const TemporalHistory& h) const override { return buffers.debug(h.cur); }

  protected:
    B buffers;
};

} // namespace bmfr
