// The debug views a CUDA filter gives (Filter::debug), brought to the host in the host
// backends' layout: two colour images, and the history length and accept mask as floats.
#pragma once
#include "backend/cuda/device_frame.h"
#include "core/half.h"
#include <algorithm>
#include <type_traits>

namespace bmfr::cuda {

struct DebugCopies {
    ImageF first, second, lengthF, acceptF;
    ImageU8 length, accept;
    Image<Half> half; ///< a first image kept as halves, before widening

    /// Downloads the four on the frame's stream and waits; `first` as floats or halves.
    template <class T>
    void capture(DeviceFrame& frame, const DeviceImage<T>& firstOnDevice,
                 const DeviceImageF& secondOnDevice, const DeviceImageU8& lengthOnDevice,
                 const DeviceImageU8& acceptOnDevice) {
        const cudaStream_t st = frame.get();
        if constexpr (std::is_same_v<T, float>)
            firstOnDevice.download(first, st);
        else
            firstOnDevice.download(half, st);
        secondOnDevice.download(second, st);
        lengthOnDevice.download(length, st);
        acceptOnDevice.download(accept, st);
        frame.synchronize();
        if constexpr (!std::is_same_v<T, float>) {
            first.resize(half.width, half.height, half.channels);
            std::copy(half.pixels.begin(), half.pixels.end(), first.data());
        }
        widenToFloat(length, lengthF);
        widenToFloat(accept, acceptF);
    }
    DebugBuffers views() const { return {view(first), view(second), view(lengthF), view(acceptF)}; }
};

} // namespace bmfr::cuda
