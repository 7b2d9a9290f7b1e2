// A frame's input planes on the device: the staged host planes (temporal/input_staging.h)
// uploaded once per frame into arrays kept between frames, and the same InputPlanes struct
// pointing at them for the kernels.
#pragma once
#include "backend/cuda/device_buffer.h"
#include "temporal/pixel_input.h"

namespace bmfr::cuda {

class DeviceInput {
  public:
    /// Uploads every plane `host` has, ordered on `stream`; returns the device planes (valid
    /// until the next call). Allocates only when the size or the set of planes changes.
    const InputPlanes& upload(const InputPlanes& host, cudaStream_t stream);

  private:
    static constexpr int kPlanes = 17;
    InputPlanes device_;
    DeviceArray<float> planes_[kPlanes];
    DeviceArray<float> extras_[InputPlanes::kMaxExtras];
};

} // namespace bmfr::cuda
