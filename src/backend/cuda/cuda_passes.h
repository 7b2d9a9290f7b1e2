// What the CUDA backend's passes of every filter share: they run on one GPU, made current for
// each call and the caller's device restored after; a frame in device memory is read in place
// and a host one uploaded (DeviceFrame::begin, inside the passes), and the result is written
// from device memory into the caller's view.
#pragma once
#include "backend/cuda/cuda_device.h"
#include "backend/cuda/device_frame.h"
#include "filters/filter_passes.h"
#include <optional>

namespace bmfr::cuda {

template <class S> class CudaPasses : public PassesFor<S> {
  public:
    /// Constructed with `device` current (cuda::makePasses).
    explicit CudaPasses(int device) : device_(device) {}

    void allocate(int w, int h, const S& settings, int threads) final {
        const DeviceScope on(device_);
        allocateOnDevice(w, h, settings, threads);
    }
    PassCounters run(const PassContext<S>& ctx, StageTimes& times) final {
        const DeviceScope on(device_);
        return runOnDevice(ctx, times);
    }
    void captureDebug(const TemporalHistory& history) final {
        const DeviceScope on(device_);
        captureDebugOnDevice(history);
    }
    bool readsDeviceMemory() const final { return true; }
    /// Only the size: the passes stage the frame themselves, on their stream.
    const InputPlanes& stage(const FrameInput& frame) final {
        planes_ = InputPlanes{};
        planes_.width = frame.color.width;
        planes_.height = frame.color.height;
        return planes_;
    }
    void write(const ImageView& result, const MutableImageView& out, void* stream) final {
        const DeviceScope on(device_);
        writeResult(result, out, stream);
        // On the caller's stream the copy reads the output after the frame's end.
        if (frame_.onDevice() && stream) frame_.extendLastFrame(static_cast<cudaStream_t>(stream));
    }

  protected:
    virtual void allocateOnDevice(int w, int h, const S& settings, int threads) = 0;
    virtual PassCounters runOnDevice(const PassContext<S>& ctx, StageTimes& times) = 0;
    virtual void captureDebugOnDevice(const TemporalHistory& history) = 0;
    int device() const { return device_; }
    /// The first statement of a derived destructor: waits for the filter's last work, so that
    /// the derived class's buffers are then freed after it, with this GPU current; this base's
    /// destruction, which comes after, restores the caller's device. Never throws (a
    /// destructor's): at process exit the runtime may already be gone.
    void leaveOnDevice() noexcept {
        try {
            leaving_.emplace(device_);
            frame_.waitForLastFrame();
        } catch (...) {
        }
    }

  private:
    std::optional<DeviceScope> leaving_; ///< declared first, so destroyed last: after frame_

  protected:
    DeviceFrame frame_; ///< the stream, staging and timing of every frame

  private:
    int device_;
    InputPlanes planes_;
};

/// The passes of settings S on GPU `device`, made with it current.
template <class S, class Passes> std::unique_ptr<PassesFor<S>> makeOnDevice(int device) {
    const DeviceScope on(device);
    return std::make_unique<Passes>(device);
}

} // namespace bmfr::cuda
