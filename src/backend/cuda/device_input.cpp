#include "backend/cuda/device_input.h"
#include "backend/cuda/image_copy.h"

namespace bmfr::cuda {

const float* DeviceInput::plane(const ImageView& v, int channels, int slot, int first,
                                cudaStream_t s) {
    const bool packed = isPacked(v, channels, first);
    if (packed && v.memory == Memory::Cuda) return v.data;
    const size_t w = size_t(v.width), h = size_t(v.height), c = size_t(channels);
    DeviceArray<float>& out = planes_[slot];
    out.resize(w * h * c);
    if (packed) {
        check(cudaMemcpyAsync(out.data(), v.data, w * h * c * sizeof(float), cudaMemcpyHostToDevice,
                              s),
              "input upload");
        return out.data();
    }
    const float* rows = v.data;
    const size_t pitch = size_t(v.stride()) * sizeof(float);
    if (v.memory == Memory::Host) { // the rows as they are (the last one may end early)
        rows_[slot].resize(size_t(v.stride()) * h);
        check(cudaMemcpy2DAsync(rows_[slot].data(), pitch, v.data, pitch,
                                w * size_t(v.channels) * sizeof(float), h, cudaMemcpyHostToDevice,
                                s),
              "input upload");
        rows = rows_[slot].data();
    }
    launchPackChannels(rows, v.channels, v.stride(), first, channels, v.width, v.height, out.data(),
                       s);
    return out.data();
}

const InputPlanes& DeviceInput::stage(const FrameInput& frame, cudaStream_t stream) {
    const AllocationStream on(stream); // the frame's stream waited for the previous frame
    device_ = stagePlanes(frame, [&](const ImageView& v, int channels, int slot, int first) {
        return plane(v, channels, slot, first, stream);
    });
    return device_;
}

} // namespace bmfr::cuda
