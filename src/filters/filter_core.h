// The one frame loop every filter runs: check the input, start the history, stage the input,
// run the backend's passes, keep the debug buffers, end the frame. A filter adds its own steps
// through hooks (FilterHooks); the public classes reach it through FrameLoop.
#pragma once
#include "core/parallel.h"
#include "filters/filter_passes.h"
#include "temporal/frame_checks.h"
#include "temporal/history.h"
#include <bmfr/error.h>
#include <bmfr/filter.h>
#include <memory>

namespace bmfr {

/// What TemporalFilter forwards to: one filter's state and its frame loop.
class FrameLoop {
  public:
    virtual ~FrameLoop() = default;
    virtual const char* name() const = 0;
    virtual ImageView denoise(const FrameInput& frame) = 0;
    virtual ImageView denoise(const FrameInput& frame, const MutableImageView& out) = 0;
    virtual void reset() = 0;
    virtual void setDebugOutputs(bool enabled) = 0;
    virtual DebugBuffers debug() const = 0;
    virtual const FrameStats& stats() const = 0;
};

/// A filter's own steps in the frame loop; the default has none.
template <class S> struct FilterHooks {
    /// Extra buffers (FrameInput::extras) the settings read.
    int extrasNeeded(const S&) const { return 0; }
    /// Throws bmfr::Error for a frame this filter cannot run on, before the shared checks.
    void check(const S&, const FrameInput&) const {}
    /// The settings the passes run with on this frame (called before the history moves on);
    /// sets `changed` when the buffers must be allocated again for them.
    const S& select(const S& settings, const FrameInput&, const TemporalHistory&, bool& changed) {
        changed = false;
        return settings;
    }
    /// The settings whose buffers hold those of every frame's select() (Device::reserve).
    S widest(const S& settings) const { return settings; }
};

/// A filter's state: settings, the backend's passes P, threads, history and stats.
template <class S, class Hooks = FilterHooks<S>, class P = PassesFor<S>>
struct FilterCore final : FrameLoop {
    const char* filterName;
    S settings;
    std::unique_ptr<P> passes;
    std::shared_ptr<ThreadPool> pool; ///< its Device's
    TemporalHistory history;
    FrameStats counts;
    Hooks hooks;
    bool keepDebug = false;

    FilterCore(const char* name, const S& s, std::unique_ptr<P> p,
               std::shared_ptr<ThreadPool> threads)
        : filterName(name), settings(s), passes(std::move(p)), pool(std::move(threads)) {}

    /// Sizes the buffers for w x h frames ahead of the first.
    void reserve(int w, int h) {
        passes->allocate(w, h, hooks.widest(settings), pool->threadCount());
    }

    const char* name() const override { return filterName; }

    /// Throws bmfr::Error for bad input before the history moves on.
    ImageView denoise(const FrameInput& frame) override {
        hooks.check(settings, frame);
        checkFrameInput(frame, hooks.extrasNeeded(settings), backendName(settings.backend),
                        passes->readsDeviceMemory());
        bool changed = false;
        const S& active = hooks.select(settings, frame, history, changed);
        try {
            if (history.begin(frame) || changed)
                passes->allocate(history.width, history.height, active, pool->threadCount());
            const PassContext<S> ctx{active, passes->stage(frame), frame, history, *pool};
            counts.times.clear();
            const PassCounters c = passes->run(ctx, counts.times);
            counts.nonFiniteInputs = c.nonFinite;
            counts.discardedPixels = c.discarded;
            if (keepDebug) passes->captureDebug(history);
            const int slot = history.cur;
            history.end(frame);
            return passes->output(slot);
        } catch (...) {
            // A frame that failed half way (out of memory, a device error) leaves buffers of
            // unknown size and a half-written slot: the next frame starts over, allocating.
            history = TemporalHistory{};
            throw;
        }
    }
    ImageView denoise(const FrameInput& frame, const MutableImageView& out) override {
        checkOutput(out, frame.color.width, frame.color.height); // before the history moves on
        if (out.memory == Memory::Cuda && frame.color.memory == Memory::Host)
            throw Error("output buffer is in CUDA device memory, the frame's buffers in host "
                        "memory");
        const ImageView result = denoise(frame);
        passes->write(result, out, frame.cudaStream);
        return result;
    }
    void reset() override { history.reset(); }
    void setDebugOutputs(bool enabled) override { keepDebug = enabled; }
    DebugBuffers debug() const override {
        if (!keepDebug || history.width == 0) return {};
        return passes->debug(history);
    }
    const FrameStats& stats() const override { return counts; }
};

} // namespace bmfr
