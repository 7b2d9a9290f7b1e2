#include "filters/filter_core.h"
#include "temporal/input_staging.h"
#include <bmfr/error.h>

namespace bmfr {

TemporalFilter::TemporalFilter(std::unique_ptr<FrameLoop> loop) : loop_(std::move(loop)) {}
TemporalFilter::~TemporalFilter() = default;
TemporalFilter::TemporalFilter(TemporalFilter&&) noexcept = default;
TemporalFilter& TemporalFilter::operator=(TemporalFilter&&) noexcept = default;

ImageView TemporalFilter::denoise(const FrameInput& frame) {
    return loop_->denoise(frame);
}
ImageView TemporalFilter::denoise(const FrameInput& frame, const MutableImageView& out) {
    return loop_->denoise(frame, out);
}
void TemporalFilter::reset() {
    loop_->reset();
}
const FrameStats& TemporalFilter::lastStats() const {
    return loop_->stats();
}
const char* TemporalFilter::name() const {
    return loop_->name();
}
void TemporalFilter::setDebugOutputs(bool enabled) {
    loop_->setDebugOutputs(enabled);
}
DebugBuffers TemporalFilter::debug() const {
    return loop_->debug();
}

/// A Filter of the caller's own: host results only.
ImageView Filter::denoise(const FrameInput& frame, const MutableImageView& out) {
    checkOutput(out, frame.color.width, frame.color.height); // before the history moves on
    if (out.memory == Memory::Cuda)
        throw Error("output buffer is in CUDA device memory; this filter writes host memory");
    const ImageView result = denoise(frame);
    writeOutput(result, out);
    return result;
}

} // namespace bmfr
