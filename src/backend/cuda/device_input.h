// A frame's input planes on the device, staged from the caller's buffers in either memory:
// packed device buffers are read in place; host buffers are uploaded; RGBA or padded rows are
// packed by a kernel. The arrays are kept between frames; the planes are the InputPlanes the
// kernels read.
#pragma once
#include "backend/cuda/device_buffer.h"
#include "temporal/input_staging.h"

namespace bmfr::cuda {

class DeviceInput {
  public:
    /// The frame's planes on the device, staged on `stream` (valid until the next call).
    /// Allocates only when the size or the set of buffers changes.
    const InputPlanes& stage(const FrameInput& frame, cudaStream_t stream);

  private:
    const float* plane(const ImageView& v, int channels, int slot, int first, cudaStream_t s);
    InputPlanes device_;
    DeviceArray<float> planes_[kStagedPlanes]; ///< packed planes, by stagePlanes slot
    DeviceArray<float> rows_[kStagedPlanes];   ///< uploaded rows of unpacked host buffers
};

} // namespace bmfr::cuda
