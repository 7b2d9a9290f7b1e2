// The CUDA backend's Mara 2017: the reference backend's stages
// (filters/mara2017/mara_stage_loops.h) on the CUDA executor, one kernel per loop on one stream,
// over device-resident buffers, then the shared TAA. The frame's spiral and tap tables are
// built on the host, as the reference builds them, and copied up. The output (for host frames)
// and two counters come down, with at most one synchronisation.
#include "backend/backend_registry.h"
#include "backend/cuda/cuda_executor.h"
#include "backend/cuda/cuda_passes.h"
#include "backend/cuda/debug_copies.h"
#include "backend/cuda/staged_upload.h"
#include "filters/mara2017/mara_stage_loops.h"
#include "temporal/taa_stage.h"
#include <vector>

namespace bmfr::cuda {

namespace {

/// One table on the device, copied up each frame from its host twin.
template <class T> struct DeviceTable {
    DeviceArray<T> device;
    StagedUpload upload;
    const T* copy(const std::vector<T>& host, cudaStream_t stream) {
        upload.copy(device.data(), host.data(), host.size() * sizeof(T), stream);
        return device.data();
    }
};

class CudaMaraPasses final : public CudaPasses<Mara2017Settings> {
  public:
    using CudaPasses::CudaPasses;
    ~CudaMaraPasses() override { leaveOnDevice(); }

    void allocateOnDevice(int w, int h, const Mara2017Settings& s, int) override {
        const size_t pre = size_t(s.preTaps) * kMaraSpiralRotations;
        const size_t fin = size_t(s.finalTaps) * kMaraSpiralRotations;
        frame_.allocate([&](cudaStream_t) {
            b_.allocate(w, h);
            preSpiral_.device.resize(2 * pre), finalSpiral_.device.resize(2 * fin);
            preOffsets_.device.resize(2 * pre), preGauss_.device.resize(pre);
        });
        tables_.reserve(s);
        for (ImageF& o : output_) o.resize(w, h, 3);
    }

    PassCounters runOnDevice(const MaraPassContext& ctx, StageTimes& times) override {
        const Mara2017Settings& s = ctx.settings;
        const TemporalHistory& h = ctx.history;
        const InputPlanes& in = frame_.begin(ctx.frame);
        const cudaStream_t st = frame_.get(); // the caller's or ours: begin() chose
        const MaraPassContext on{s, in, ctx.frame, h, ctx.pool};
        MaraFrame f = b_.frame(on);
        tables_.build(s, f);
        f.preSpiral = preSpiral_.copy(tables_.preSpiral, st);
        f.finalSpiral = finalSpiral_.copy(tables_.finalSpiral, st);
        f.preOffsets = preOffsets_.copy(tables_.preOffsets, st);
        f.preGauss = preGauss_.copy(tables_.preGauss, st);
        const CudaExecutor e{st};

        maraMatteTemporalStage(e, f, frame_.nonFinite());
        countDiscarded(e, f.accept, long(f.width) * f.height, h.hasHistory(), frame_.discarded());
        frame_.mark("matte temporal");
        if (s.preBilateral)
            maraPreBilateralStage(e, f);
        else
            maraKeepTemporalStage(e, f);
        frame_.mark("pre-bilateral");
        maraDisocclusionStage(e, f);
        frame_.mark("disocclusion");
        if (s.median) maraMedianStage(e, f);
        frame_.mark("firefly median");
        maraMatteBilateralStage(e, f, s.median ? f.median : f.temporal);
        frame_.mark("matte bilateral");
        if (f.glossy) {
            maraGlossyTemporalStage(e, f);
            frame_.mark("glossy temporal");
            maraGlossyBilateralStage(e, f);
            frame_.mark("glossy bilateral");
        }
        if (s.taa && h.hasHistory()) {
            maraComposeStage(e, f);
            taaStage(e, b_.taaInputs(on), b_.ycocg.data(), b_.output[h.cur].data(), true);
        } else { // straight into the output, not through a copy
            MaraFrame out = f;
            out.composed = b_.output[h.cur].data();
            maraComposeStage(e, out);
        }
        frame_.mark("compose");

        if (!frame_.onDevice()) b_.output[h.cur].download(output_[h.cur], st);
        return frame_.finish(times);
    }

    /// In the memory the frame's buffers were in.
    ImageView output(int slot) const override {
        return frame_.onDevice() ? deviceView(b_.output[slot]) : view(output_[slot]);
    }

    void captureDebugOnDevice(const TemporalHistory& h) override {
        debug_.capture(frame_, b_.temporal, b_.matteOut, b_.count[h.cur], b_.accept);
    }
    DebugBuffers debug(const TemporalHistory&) const override { return debug_.views(); }

  private:
    MaraImages<DeviceImageF, DeviceImageU8> b_;
    MaraTables tables_;
    DeviceTable<float> preSpiral_, finalSpiral_, preGauss_;
    DeviceTable<int> preOffsets_;
    ImageF output_[2];
    DebugCopies debug_;
};

} // namespace

template <> std::unique_ptr<MaraPasses> makePasses<Mara2017Settings>(int device) {
    return makeOnDevice<Mara2017Settings, CudaMaraPasses>(device);
}

} // namespace bmfr::cuda
