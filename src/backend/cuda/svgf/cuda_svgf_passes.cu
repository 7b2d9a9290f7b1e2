// The CUDA backend's SVGF: its stages (filters/svgf/svgf_stage_loops.h) and the shared TAA on
// the CUDA executor, as kernels on one stream over device-resident buffers. The output (for
// host frames) and the non-finite count come down, with at most one synchronisation.
#include "backend/backend_registry.h"
#include "backend/cuda/cuda_executor.h"
#include "backend/cuda/cuda_passes.h"
#include "backend/cuda/debug_copies.h"
#include "filters/svgf/svgf_passes.h"
#include "filters/svgf/svgf_stage_loops.h"
#include "temporal/taa_stage.h"

namespace bmfr::cuda {

namespace {

class CudaSvgfPasses final : public CudaPasses<SvgfSettings> {
  public:
    using CudaPasses::CudaPasses;
    ~CudaSvgfPasses() override { leaveOnDevice(); }

    void allocateOnDevice(int w, int h, const SvgfSettings&, int) override {
        frame_.allocate([&](cudaStream_t) {
            b_.allocate(w, h);
            ycocg_.resize(w, h, 3);
        });
        for (ImageF& o : output_) o.resize(w, h, 3);
    }

    PassCounters runOnDevice(const SvgfPassContext& ctx, StageTimes& times) override {
        const SvgfSettings& s = ctx.settings;
        const TemporalHistory& h = ctx.history;
        const InputPlanes& in = frame_.begin(ctx.frame);
        const cudaStream_t st = frame_.get(); // the caller's or ours: begin() chose

        const SvgfFrame f = b_.frame(ctx, in);
        const CudaExecutor e{st};
        svgfAccumulateStage(e, f, frame_.nonFinite(), frame_.discarded());
        svgfDepthGradientStage(e, f);
        frame_.mark("accumulate");
        svgfVarianceStage(e, f, s, b_.filtered[0].data(), b_.variance.data());
        frame_.mark("variance");
        const AtrousLevel guides{nullptr,         nullptr,  f.normal, f.depth,
                                 f.depthGradient, f.length, h.width,  h.height};
        const int src = svgfAtrousLevelsStage(e, s, guides, b_.filtered, b_.color[h.cur].data());
        outputLevel_ = src;
        svgfRemodulateStage(e, b_.filtered[src].data(), in, s.albedoEpsilon, b_.remodulated.data());
        frame_.mark("atrous");

        const TaaInputs taa =
            taaInputs(b_.remodulated.data(), b_.output[1 - h.cur].data(), b_.previousPixel.data(),
                      h.width, h.height, s, b_.accept.data());
        taaStage(e, taa, ycocg_.data(), b_.output[h.cur].data(), s.taa && h.hasHistory());
        frame_.mark("taa");

        if (!frame_.onDevice()) b_.output[h.cur].download(output_[h.cur], st);
        return frame_.finish(times);
    }

    /// In the memory the frame's buffers were in.
    ImageView output(int slot) const override {
        return frame_.onDevice() ? deviceView(b_.output[slot]) : view(output_[slot]);
    }
    /// On the host, brought there only when asked for: most callers never look at it.
    ImageView variance() const override {
        if (frame_.onDevice()) return deviceView(b_.variance);
        const DeviceScope on(device());
        b_.variance.download(variance_, frame_.get());
        frame_.synchronize();
        return view(variance_);
    }

    void captureDebugOnDevice(const TemporalHistory& h) override {
        debug_.capture(frame_, b_.integrated, b_.filtered[outputLevel_], b_.historyLength[h.cur],
                       b_.accept);
        // The level holds colour and variance: its colour, as the host backends' view.
        finalLevel_.resize(debug_.second.width, debug_.second.height, 3);
        for (long i = 0; i < finalLevel_.pixelCount(); ++i)
            store3(finalLevel_.data(), i, load3Stride4(debug_.second.data(), i));
    }
    DebugBuffers debug(const TemporalHistory&) const override {
        DebugBuffers d = debug_.views();
        d.fitted = view(finalLevel_);
        return d;
    }

  private:
    SvgfImages<DeviceImageF, DeviceImageU8> b_;
    DeviceImageF ycocg_;
    int outputLevel_ = 0;
    ImageF output_[2], finalLevel_;
    mutable ImageF variance_;
    DebugCopies debug_;
};

} // namespace

template <> std::unique_ptr<SvgfPasses> makePasses<SvgfSettings>(int device) {
    return makeOnDevice<SvgfSettings, CudaSvgfPasses>(device);
}

} // namespace bmfr::cuda
