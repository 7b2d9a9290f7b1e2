// What a filter object carries between frames and the frame loop that SVGF and WALR share:
// check the input, start the history, stage the input, run the backend's passes, keep the debug
// buffers, end the frame. (BMFR's denoiser adds its block grid and noise, so it has its own.)
#pragma once
#include "core/parallel.h"
#include "temporal/frame_checks.h"
#include "temporal/history.h"
#include "temporal/input_staging.h"
#include <bmfr/filter.h>
#include <memory>

namespace bmfr {

/// Inputs of one frame's passes, for a filter with settings S.
template <class S> struct PassContext {
    const S& settings;
    const InputPlanes& input;
    const FrameInput& frame; ///< for the cameras
    const TemporalHistory& history;
    ThreadPool& pool;
};

/// A filter's state: settings, the backend's passes P, threads, history, staging and stats.
template <class S, class P> struct FilterCore {
    S settings;
    std::unique_ptr<P> passes;
    ThreadPool pool;
    TemporalHistory history;
    InputStaging staging;
    FrameStats stats;
    bool debug = false;

    FilterCore(const S& s, std::unique_ptr<P> p)
        : settings(s), passes(std::move(p)), pool(s.threads) {}

    /// Runs one frame through the passes; returns the history slot it wrote. Throws
    /// bmfr::Error for bad input before the history moves on.
    int runFrame(const FrameInput& frame) {
        checkFrameInput(frame, 0, settings.backend);
        if (history.begin(frame)) passes->allocate(history.width, history.height);
        const PassContext<S> ctx{settings, staging.stage(frame, settings.backend == Backend::Cuda),
                                 frame, history, pool};
        stats.times.clear();
        stats.nonFiniteInputs = passes->run(ctx, stats.times);
        if (debug) passes->captureDebug(history.cur);
        const int slot = history.cur;
        history.end(frame);
        return slot;
    }
    DebugBuffers debugBuffers() const {
        if (!debug || history.width == 0) return {};
        return passes->debug(history.cur);
    }
};

} // namespace bmfr
