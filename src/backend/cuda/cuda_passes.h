// What the CUDA backend's passes of every filter share: a frame in device memory is read in
// place and a host one uploaded (DeviceFrame::begin, inside the passes), and the result is
// written from device memory into the caller's view.
#pragma once
#include "backend/cuda/cuda_device.h"
#include "filters/filter_passes.h"

namespace bmfr::cuda {

template <class S> class CudaPasses : public PassesFor<S> {
  public:
    CudaPasses() { requireDevice(); }
    bool readsDeviceMemory() const override { return true; }
    /// Only the size: the passes stage the frame themselves, on their stream.
    const InputPlanes& stage(const FrameInput& frame) override {
        planes_ = InputPlanes{};
        planes_.width = frame.color.width;
        planes_.height = frame.color.height;
        return planes_;
    }
    void write(const ImageView& result, const MutableImageView& out, void* stream) override {
        writeResult(result, out, stream);
    }

  private:
    InputPlanes planes_;
};

} // namespace bmfr::cuda
