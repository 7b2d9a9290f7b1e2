// What every CUDA filter's passes do around their kernels each frame: choose the stream (the
// caller's, for device buffers, or the passes' own), order the frame after the previous one on
// the device, stage the input, time the stages with events, and end the frame: with one
// synchronisation, or with none on the caller's stream, whose times and counts are then read
// once a later frame finds them done.
#pragma once
#include "backend/cuda/device_input.h"
#include "backend/cuda/stage_events.h"
#include "core/executor.h"
#include "filters/filter_passes.h"

namespace bmfr::cuda {

class DeviceFrame {
  public:
    static constexpr int kCounters = 2;

    DeviceFrame();
    ~DeviceFrame();
    DeviceFrame(const DeviceFrame&) = delete;
    DeviceFrame& operator=(const DeviceFrame&) = delete;

    /// Runs `allocate(stream)`, whose device allocations (AllocationStream) and uploads go on
    /// `stream`, ordered after the previous frame and before the next, with no waiting.
    template <class F> void allocate(F&& allocate) {
        followCallersStream();
        check(cudaStreamWaitEvent(own_.get(), end_, 0), "cudaStreamWaitEvent");
        {
            const AllocationStream on(own_.get());
            allocate(own_.get());
        }
        check(cudaEventRecord(end_, own_.get()), "cudaEventRecord");
    }
    /// Starts a frame: zeroes its counters, stages its input (the "upload" stage) and returns
    /// the device planes.
    const InputPlanes& begin(const FrameInput& frame);
    /// The frame's counts of non-finite inputs and of pixels that lost their history.
    FrameCounter nonFinite() { return {counters_.data()}; }
    FrameCounter discarded() { return {counters_.data() + 1}; }
    /// The stream this frame runs on.
    cudaStream_t get() const { return current_; }
    /// True when this frame's buffers, and so its output, are in device memory.
    bool onDevice() const { return onDevice_; }
    /// Ends the stage `name` (a string literal).
    void mark(const char* name) { events_.mark(name, current_); }
    /// Ends the frame after the downloads queued on its stream (the "download" stage). Adds
    /// stage times to `times` and returns the counts: this frame's after waiting for it, or, on
    /// the caller's stream, those of the previous frame if it had finished when this one began
    /// (else none, and zeros).
    PassCounters finish(StageTimes& times);
    /// Waits for the frame's stream (debug downloads).
    void synchronize() const;
    /// The last frame's work goes on to `stream`'s work queued so far (the output written into
    /// the caller's view): the next frame, a reallocation or the destruction waits for it too.
    void extendLastFrame(cudaStream_t stream);
    /// Waits for the last frame's (or allocation's) work, wherever it ran: before buffers it
    /// used are freed outside the stream order.
    void waitForLastFrame() const;

  private:
    /// After a frame on the caller's stream: end_ moves to that stream's tail, past the work the
    /// caller queued there that reads the frame's output, before the output is overwritten or
    /// freed (the stream must still exist: FrameInput::cudaStream).
    void followCallersStream();

    Stream own_;
    DeviceArray<unsigned long long> counters_; ///< kCounters, on the device
    cudaStream_t current_ = nullptr;
    bool onDevice_ = false, deferred_ = false;
    StageEvents events_;
    DeviceInput input_;
    cudaEvent_t end_ = nullptr;                ///< the previous frame's (or allocation's) last work
    cudaEvent_t legacy_ = nullptr;             ///< the legacy default stream's work, waited for
    unsigned long long* hostCounts_ = nullptr; ///< pinned, written by the stream
    bool pending_ = false;                     ///< a deferred frame's stats are still to be read
    StageTimes previousTimes_;
    unsigned long long previousCounts_[kCounters] = {};
};

} // namespace bmfr::cuda
