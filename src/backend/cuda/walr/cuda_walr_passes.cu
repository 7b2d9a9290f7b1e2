// The CUDA backend's WALR: the reference backend's stages (filters/walr/walr_stages.h) on the
// CUDA executor, one kernel per loop on one stream, over device-resident buffers. The output
// (for host frames) and two counters come down, with at most one synchronisation.
#include "backend/backend_registry.h"
#include "backend/cuda/cuda_executor.h"
#include "backend/cuda/cuda_passes.h"
#include "backend/cuda/debug_copies.h"
#include "filters/walr/walr_stages.h"

namespace bmfr::cuda {

namespace {

class CudaWalrPasses final : public CudaPasses<WalrSettings> {
  public:
    using CudaPasses::CudaPasses;
    ~CudaWalrPasses() override { leaveOnDevice(); }

    void allocateOnDevice(int w, int h, const WalrSettings& s, int) override {
        frame_.allocate([&](cudaStream_t) {
            b_.allocate(w, h);
            trace_.resize(walrSteppedTrace(s) ? long(w) * h : 0);
        });
        output_.resize(w, h, 3);
    }

    PassCounters runOnDevice(const WalrPassContext& ctx, StageTimes& times) override {
        const InputPlanes& in = frame_.begin(ctx.frame);
        const cudaStream_t st = frame_.get(); // the caller's or ours: begin() chose
        const WalrPassContext on{ctx.settings, in, ctx.frame, ctx.history, ctx.pool};
        const CudaExecutor e{st};

        walrPreprocessStage(e, on, b_, frame_.nonFinite());
        countDiscarded(e, b_.accept.data(), b_.accept.pixelCount(), ctx.history.hasHistory(),
                       frame_.discarded());
        frame_.mark("preprocess");
        if (ctx.settings.solver == WalrSolver::Refwlr) {
            walrRefwlrStage(e, on, b_);
        } else {
            walrAtrousStage(e, on, b_, trace_);
            walrSolveStage(e, on, b_);
        }
        frame_.mark("spatial");
        walrPostprocessStage(e, on, b_);
        frame_.mark("postprocess");

        if (!frame_.onDevice()) b_.output.download(output_, st);
        return frame_.finish(times);
    }

    /// In the memory the frame's buffers were in.
    ImageView output(int) const override {
        return frame_.onDevice() ? deviceView(b_.output) : view(output_);
    }

    void captureDebugOnDevice(const TemporalHistory& h) override {
        debug_.capture(frame_, b_.pre[h.cur], b_.spatial, b_.count[h.cur], b_.accept);
    }
    DebugBuffers debug(const TemporalHistory&) const override { return debug_.views(); }

  private:
    WalrImages<DeviceImageF, DeviceImageU8> b_;
    SteppedTraceStore<DeviceArray> trace_;
    ImageF output_;
    DebugCopies debug_;
};

} // namespace

template <> std::unique_ptr<WalrPasses> makePasses<WalrSettings>(int device) {
    return makeOnDevice<WalrSettings, CudaWalrPasses>(device);
}

} // namespace bmfr::cuda
