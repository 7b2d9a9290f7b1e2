#include "backend/cuda/device_frame.h"
#include "temporal/frame_checks.h"

namespace bmfr::cuda {

DeviceFrame::DeviceFrame() {
    check(cudaEventCreateWithFlags(&end_, cudaEventDisableTiming), "cudaEventCreate");
    check(cudaEventCreateWithFlags(&legacy_, cudaEventDisableTiming), "cudaEventCreate");
    check(cudaMallocHost(reinterpret_cast<void**>(&hostCounts_), sizeof(*hostCounts_) * kCounters),
          "cudaMallocHost");
    current_ = own_.get();
}

DeviceFrame::~DeviceFrame() {
    cudaEventSynchronize(end_); // the last frame's copies into hostCounts_
    cudaEventDestroy(end_);
    cudaEventDestroy(legacy_);
    cudaFreeHost(hostCounts_);
}

const InputPlanes& DeviceFrame::begin(const FrameInput& frame) {
    // A deferred frame's stats, if it is done by now (never waiting for it).
    previousTimes_.clear();
    for (unsigned long long& c : previousCounts_) c = 0;
    if (pending_ && cudaEventQuery(end_) == cudaSuccess) {
        events_.report(previousTimes_);
        for (int k = 0; k < kCounters; ++k) previousCounts_[k] = hostCounts_[k];
    }
    pending_ = false;

    onDevice_ = inDeviceMemory(frame);
    deferred_ = onDevice_ && frame.cudaStream;
    current_ = deferred_ ? static_cast<cudaStream_t>(frame.cudaStream) : own_.get();
    // The history was written on whichever stream ran the previous frame.
    check(cudaStreamWaitEvent(current_, end_, 0), "cudaStreamWaitEvent");
    if (onDevice_ && !deferred_) {
        // Device buffers without a stream: the caller may have filled them on the legacy
        // default stream, which a non-blocking stream is not ordered after.
        check(cudaEventRecord(legacy_, cudaStreamLegacy), "cudaEventRecord");
        check(cudaStreamWaitEvent(current_, legacy_, 0), "cudaStreamWaitEvent");
    }
    events_.begin(current_);
    const InputPlanes& in = input_.stage(frame, current_);
    events_.mark("upload", current_);
    return in;
}

void DeviceFrame::finish(const unsigned long long* deviceCounters, StageTimes& times,
                         unsigned long long* counts) {
    check(cudaMemcpyAsync(hostCounts_, deviceCounters, sizeof(*hostCounts_) * kCounters,
                          cudaMemcpyDeviceToHost, current_),
          "counter download");
    events_.mark("download", current_);
    check(cudaEventRecord(end_, current_), "cudaEventRecord");
    if (deferred_) {
        pending_ = true;
        for (int k = 0; k < previousTimes_.count; ++k)
            times.add(previousTimes_.name[k], previousTimes_.ms[k]);
        for (int k = 0; k < kCounters; ++k) counts[k] = previousCounts_[k];
        return;
    }
    synchronize();
    events_.report(times);
    for (int k = 0; k < kCounters; ++k) counts[k] = hostCounts_[k];
}

void DeviceFrame::waitForLastFrame() const {
    check(cudaEventSynchronize(end_), "cudaEventSynchronize");
}

void DeviceFrame::extendLastFrame(cudaStream_t stream) {
    check(cudaEventRecord(end_, stream), "cudaEventRecord");
}

void DeviceFrame::synchronize() const {
    check(cudaStreamSynchronize(current_), "cudaStreamSynchronize");
}

} // namespace bmfr::cuda
