#include "backend/cuda/device_frame.h"
#include "temporal/frame_checks.h"

namespace bmfr::cuda {

DeviceFrame::DeviceFrame() {
    check(cudaEventCreateWithFlags(&end_, cudaEventDisableTiming), "cudaEventCreate");
    check(cudaEventCreateWithFlags(&legacy_, cudaEventDisableTiming), "cudaEventCreate");
    check(cudaMallocHost(reinterpret_cast<void**>(&hostCounts_), sizeof(*hostCounts_) * kCounters),
          "cudaMallocHost");
    current_ = own_.get();
    {
        const AllocationStream on(current_);
        counters_.resize(kCounters);
    }
    check(cudaEventRecord(end_, current_), "cudaEventRecord"); // the first frame waits for it
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
    const cudaStream_t next =
        onDevice_ && frame.cudaStream ? static_cast<cudaStream_t>(frame.cudaStream) : own_.get();
    if (next != current_) followCallersStream(); // the last output is overwritten from here
    deferred_ = onDevice_ && frame.cudaStream;
    current_ = next;
    // The history was written on whichever stream ran the previous frame.
    check(cudaStreamWaitEvent(current_, end_, 0), "cudaStreamWaitEvent");
    if (onDevice_ && !deferred_) {
        // Device buffers without a stream: the caller may have filled them on the legacy
        // default stream, which a non-blocking stream is not ordered after.
        check(cudaEventRecord(legacy_, cudaStreamLegacy), "cudaEventRecord");
        check(cudaStreamWaitEvent(current_, legacy_, 0), "cudaStreamWaitEvent");
    }
    check(cudaMemsetAsync(counters_.data(), 0, counters_.bytes(), current_), "counter reset");
    events_.begin(current_);
    const InputPlanes& in = input_.stage(frame, current_);
    events_.mark("upload", current_);
    return in;
}

PassCounters DeviceFrame::finish(StageTimes& times) {
    check(cudaMemcpyAsync(hostCounts_, counters_.data(), sizeof(*hostCounts_) * kCounters,
                          cudaMemcpyDeviceToHost, current_),
          "counter download");
    events_.mark("download", current_);
    check(cudaEventRecord(end_, current_), "cudaEventRecord");
    const unsigned long long* counts = previousCounts_;
    if (deferred_) {
        pending_ = true;
        for (int k = 0; k < previousTimes_.count; ++k)
            times.add(previousTimes_.name[k], previousTimes_.ms[k]);
    } else {
        synchronize();
        events_.report(times);
        counts = hostCounts_;
    }
    return {int64_t(counts[0]), int64_t(counts[1])};
}

void DeviceFrame::waitForLastFrame() const {
    check(cudaEventSynchronize(end_), "cudaEventSynchronize");
}

void DeviceFrame::followCallersStream() {
    if (deferred_) check(cudaEventRecord(end_, current_), "cudaEventRecord");
}

void DeviceFrame::extendLastFrame(cudaStream_t stream) {
    check(cudaEventRecord(end_, stream), "cudaEventRecord");
}

void DeviceFrame::synchronize() const {
    check(cudaStreamSynchronize(current_), "cudaStreamSynchronize");
}

} // namespace bmfr::cuda
