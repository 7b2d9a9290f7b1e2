// The CUDA backend's BMFR: the reference backend's stages (filters/bmfr/bmfr_stage_loops.h) on
// the CUDA executor and the block-cooperative fit, as kernels on one stream, the
// history and every intermediate kept on the device between frames (as halves, the planes
// halfHistory rounds). Per frame: the input is staged (uploaded, or read in place from device
// memory), phase I, the noise and the block-cooperative fit, phase III and TAA run, and the
// output (for host frames) and two counters come down, with at most one synchronisation
// (device_frame.h).
#include "backend/backend_registry.h"
#include "backend/cuda/bmfr/cuda_bmfr_kernels.h"
#include "backend/cuda/cuda_executor.h"
#include "backend/cuda/cuda_passes.h"
#include "backend/cuda/debug_copies.h"
#include "filters/bmfr/bmfr_images.h"
#include "filters/bmfr/bmfr_pass_setup.h"
#include "filters/bmfr/bmfr_stage_loops.h"
#include "temporal/taa_stage.h"
#include <type_traits>
#include <variant>

namespace bmfr::cuda {

namespace {

/// The device images (BmfrImages; the planes halfHistory rounds as halves under it: half the
/// bytes each frame moves through them), with the fit's inputs and the frame's counters.
template <class H> struct Buffers : BmfrImages<DeviceImage, H> {
    DeviceArray<float> noise, fitScratch;
    DeviceArray<float> changeTiles; ///< adaptiveHistory: storeTileChange's record of each tile
    DeviceArray<Feature> features;
};

class CudaBmfrPasses final : public CudaPasses<BmfrSettings> {
  public:
    using CudaPasses::CudaPasses;
    ~CudaBmfrPasses() override { leaveOnDevice(); }

    void allocateOnDevice(int w, int h, const BmfrSettings& s, int) override {
        if (s.halfHistory != std::holds_alternative<Buffers<Half>>(b_)) {
            frame_.waitForLastFrame(); // its buffers are freed here
            if (s.halfHistory)
                b_.emplace<Buffers<Half>>();
            else
                b_.emplace<Buffers<float>>();
        }
        for (int k = 0; k < 2; ++k) output_[k].resize(w, h, 3);
        frame_.allocate([&](cudaStream_t st) {
            std::visit([&](auto& b) { allocateBuffers(b, w, h, s, st); }, b_);
        });
    }

    PassCounters runOnDevice(const BmfrPassContext& ctx, StageTimes& times) override {
        return std::visit([&](auto& b) { return runWith(b, ctx, times); }, b_);
    }

    /// In the memory the frame's buffers were in.
    ImageView output(int slot) const override {
        const DeviceImageF& out =
            std::visit([&](const auto& b) -> const DeviceImageF& { return b.output[slot]; }, b_);
        return frame_.onDevice() ? deviceView(out) : view(output_[slot]);
    }

    void captureDebugOnDevice(const TemporalHistory& t) override {
        std::visit([&](auto& b) { captureDebugOf(b, t); }, b_);
    }

    DebugBuffers debug(const TemporalHistory&) const override { return debug_.views(); }

  private:
    template <class H>
    void allocateBuffers(Buffers<H>& b, int w, int h, const BmfrSettings& s, cudaStream_t st) {
        b.allocate(w, h, s);
        b.changeTiles.resize(s.adaptiveHistory ? size_t(changeTileFloats(w, h)) : 0);
        const int W = s.blockSize * s.blockSize, M = int(s.features.size());
        b.noise.resize(size_t(M) * size_t(W));
        b.features.resize(size_t(M));
        // From pageable memory: staged before the call returns.
        check(cudaMemcpyAsync(b.features.data(), s.features.data(), size_t(M) * sizeof(Feature),
                              cudaMemcpyHostToDevice, st),
              "feature upload");
        plan_ = planFit(M, s.blockSize);
        const BlockGrid most = makeBlockGrid(w, h, s.blockSize, 0);
        b.fitScratch.resize(plan_.matrixInShared ? 0
                                                 : plan_.matrixFloats * size_t(most.blockCount()));
    }

    template <class H>
    PassCounters runWith(Buffers<H>& b, const BmfrPassContext& ctx, StageTimes& times) {
        const BmfrSettings& s = ctx.settings;
        const TemporalHistory& t = ctx.history;
        const int cur = t.cur, prev = 1 - cur;
        const InputPlanes& in = frame_.begin(ctx.frame);
        const cudaStream_t st = frame_.get(); // the caller's or ours: begin() chose

        const CudaExecutor e{st};
        bmfrAccumulateNoisyStage(e, noisyAccumulation(ctx, in, b), frame_.nonFinite(),
                                 frame_.discarded());
        frame_.mark("accumulate");

        if (s.stages.fitting) {
            const int W = s.blockSize * s.blockSize, M = int(s.features.size());
            bmfrNoiseStage(e, b.noise.data(), b.features.data(), M, W, s.seed,
                           uint32_t(t.frameIndex), s.noiseAmplitude);
            const BlockFitOf<H> fit = blockFit(ctx, in, b, b.features.data(), b.noise.data());
            launchFitBlocks(fit, plan_, b.fitScratch.data(), st);
            if (s.secondGrid) {
                // The shifted grid's blocks that own a history-poor pixel, as the CPU backend.
                BlockFitOf<H> second = fit;
                second.grid = secondGrid(fit.grid);
                second.fitted = b.fittedSecond.data(), second.emitters.bits = nullptr;
                launchFitBlocks(second, plan_, b.fitScratch.data(), st,
                                b.historyLength[cur].data());
                bmfrBlendSecondFitStage(e, b.fitted.data(), b.fittedSecond.data(),
                                        b.historyLength[cur].data(), long(t.width) * t.height);
            }
            if (fit.emitters.on)
                bmfrSameEmitterTapsStage(e, b.acceptMask.data(), b.previousPixel.data(),
                                         b.emitter[prev].data(), fit.emitters.bits, t.width,
                                         t.height);
        } else {
            bmfrUnfittedStage(e, b.accumulatedNoisy[cur].data(), b.fitted.data(),
                              long(b.fitted.pixels.size()));
        }
        if (const float* visibility = in.visibility; s.visibilityTaps && visibility)
            bmfrSameLitTapsStage(e, b.acceptMask.data(), b.previousPixel.data(), visibility,
                                 t.hasHistory() ? b.lit[prev].data() : nullptr, b.lit[cur].data(),
                                 t.width, t.height);
        frame_.mark("fit");

        if (s.adaptiveHistory)
            bmfrHistoryChangeStage(e, b.changeTiles.data(), b.change.data(), t.width, t.height,
                                   s.historyChangeThreshold, s.historyChangeGain);
        bmfrAccumulateFittedStage(e, fittedAccumulation(ctx, in, b), b.remodulated.data());
        frame_.mark("accumulate_fitted");

        const TaaInputs taa =
            taaInputs(b.remodulated.data(), b.output[prev].data(), b.previousPixel.data(), t.width,
                      t.height, s, b.acceptMask.data());
        taaStage(e, taa, b.ycocg.data(), b.output[cur].data(), s.taa && t.hasHistory());
        frame_.mark("taa");

        if (!frame_.onDevice()) b.output[cur].download(output_[cur], st);
        return frame_.finish(times);
    }

    template <class H> void captureDebugOf(Buffers<H>& b, const TemporalHistory& t) {
        debug_.capture(frame_, b.accumulatedNoisy[t.cur], b.fitted, b.historyLength[t.cur],
                       b.acceptMask);
    }

    std::variant<Buffers<Half>, Buffers<float>> b_;
    ImageF output_[2]; ///< for host frames
    DebugCopies debug_;
    FitPlan plan_;
};

} // namespace

template <> std::unique_ptr<BmfrPasses> makePasses<BmfrSettings>(int device) {
    return makeOnDevice<BmfrSettings, CudaBmfrPasses>(device);
}

} // namespace bmfr::cuda
