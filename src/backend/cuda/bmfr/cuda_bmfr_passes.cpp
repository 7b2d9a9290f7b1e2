// The CUDA backend's BMFR: the reference backend's stages as kernels on one stream, the
// history and every intermediate kept on the device between frames. Per frame: the input is
// staged (uploaded, or read in place from device memory), phase I, the noise and the
// block-cooperative fit, phase III and TAA run, and the output (for host frames) and two
// counters come down, with at most one synchronisation (device_frame.h).
#include "backend/backend_registry.h"
#include "backend/cuda/bmfr/cuda_bmfr_kernels.h"
#include "backend/cuda/cuda_device.h"
#include "backend/cuda/cuda_passes.h"
#include "backend/cuda/cuda_taa.h"
#include "backend/cuda/device_frame.h"
#include "filters/bmfr/bmfr_pass_setup.h"
#include "filters/bmfr/second_grid.h"
#include "filters/bmfr/visibility_taps.h"

namespace bmfr::cuda {

namespace {

struct Buffers {
    // History, [slot].
    DeviceImageF normal[2], position[2], accumulatedNoisy[2], accumulatedFitted[2], output[2];
    DeviceImageU8 historyLength[2];
    DeviceImageU8 emitter[2]; ///< BmfrSettings::excludeEmitters: the fit's emitter bits
    DeviceImageU8 lit[2];     ///< BmfrSettings::visibilityTaps: litClass of each pixel
    // This frame only.
    DeviceImageF previousPixel, fitted, remodulated, ycocg;
    DeviceImageF fittedSecond; ///< BmfrSettings::secondGrid: the shifted grid's fit
    DeviceImageU8 acceptMask;
    DeviceImageF change; ///< BmfrSettings::adaptiveHistory: recordHistoryChange's 2 channels
    DeviceArray<float> noise, fitScratch;
    DeviceArray<float> changeTiles; ///< adaptiveHistory: storeTileChange's record of each tile
    DeviceArray<Feature> features;
    DeviceArray<unsigned long long> counters; ///< non-finite inputs, discarded pixels
};

/// What comes back to the host each frame (and, on request, the debug views).
struct HostCopies {
    ImageF output[2];
    ImageF noisy, fitted, historyLengthF, acceptF;
    ImageU8 historyLength, accept;
};

class CudaBmfrPasses final : public CudaPasses<BmfrSettings> {
  public:
    using CudaPasses::CudaPasses;
    ~CudaBmfrPasses() override { leaveOnDevice(); }

    void allocateOnDevice(int w, int h, const BmfrSettings& s, int) override {
        frame_.allocate([&](cudaStream_t st) {
            Buffers& b = b_;
            for (int k = 0; k < 2; ++k) {
                b.normal[k].resize(w, h, 3), b.position[k].resize(w, h, 3);
                b.accumulatedNoisy[k].resize(w, h, 3), b.accumulatedFitted[k].resize(w, h, 3);
                b.output[k].resize(w, h, 3), b.historyLength[k].resize(w, h, 1);
                b.emitter[k].resize(s.excludeEmitters ? w : 0, s.excludeEmitters ? h : 0, 1);
                b.lit[k].resize(s.visibilityTaps ? w : 0, s.visibilityTaps ? h : 0, 1);
                host_.output[k].resize(w, h, 3);
            }
            b.previousPixel.resize(w, h, 2), b.fitted.resize(w, h, 3);
            b.fittedSecond.resize(s.secondGrid ? w : 0, s.secondGrid ? h : 0, 3);
            b.remodulated.resize(w, h, 3), b.ycocg.resize(w, h, 3), b.acceptMask.resize(w, h, 1);
            b.change.resize(s.adaptiveHistory ? w : 0, s.adaptiveHistory ? h : 0, 2);
            b.changeTiles.resize(s.adaptiveHistory ? size_t(changeTileFloats(w, h)) : 0);
            const int W = s.blockSize * s.blockSize, M = int(s.features.size());
            b.noise.resize(size_t(M) * size_t(W));
            b.features.resize(size_t(M));
            // From pageable memory: staged before the call returns.
            check(cudaMemcpyAsync(b.features.data(), s.features.data(), size_t(M) * sizeof(Feature),
                                  cudaMemcpyHostToDevice, st),
                  "feature upload");
            b.counters.resize(DeviceFrame::kCounters);
            plan_ = planFit(M, s.blockSize);
            const BlockGrid most = makeBlockGrid(w, h, s.blockSize, 0);
            b.fitScratch.resize(
                plan_.matrixInShared ? 0 : plan_.matrixFloats * size_t(most.blockCount()));
        });
    }

    PassCounters runOnDevice(const BmfrPassContext& ctx, StageTimes& times) override {
        const BmfrSettings& s = ctx.settings;
        const TemporalHistory& t = ctx.history;
        const int cur = t.cur, prev = 1 - cur;
        Buffers& b = b_;
        const InputPlanes& in = frame_.begin(ctx.frame);
        const cudaStream_t st = frame_.get(); // the caller's or ours: begin() chose
        check(cudaMemsetAsync(b.counters.data(), 0, b.counters.bytes(), st), "counter reset");

        launchAccumulateNoisy(noisyAccumulation(ctx, in, b), b.counters.data(), st);
        frame_.mark("accumulate");

        if (s.stages.fitting) {
            const int W = s.blockSize * s.blockSize, M = int(s.features.size());
            launchNoise(b.noise.data(), b.features.data(), M, W, s.seed, uint32_t(t.frameIndex),
                        s.noiseAmplitude, st);
            const BlockFit fit = blockFit(ctx, in, b, b.features.data(), b.noise.data());
            launchFitBlocks(fit, plan_, b.fitScratch.data(), st);
            if (s.secondGrid) {
                // The shifted grid's blocks that own a history-poor pixel, as the CPU backend.
                BlockFit second = fit;
                second.grid = secondGrid(fit.grid);
                second.fitted = b.fittedSecond.data(), second.emitters.bits = nullptr;
                launchFitBlocks(second, plan_, b.fitScratch.data(), st,
                                b.historyLength[cur].data());
                launchBlendSecondFit(b.fitted.data(), b.fittedSecond.data(),
                                     b.historyLength[cur].data(), long(t.width) * t.height, st);
            }
            if (fit.emitters.on)
                launchSameEmitterTaps(b.acceptMask.data(), b.previousPixel.data(),
                                      b.emitter[prev].data(), fit.emitters.bits, t.width, t.height,
                                      st);
        } else {
            check(cudaMemcpyAsync(b.fitted.data(), b.accumulatedNoisy[cur].data(),
                                  b.accumulatedNoisy[cur].pixels.bytes(), cudaMemcpyDeviceToDevice,
                                  st),
                  "fit copy");
        }
        if (const float* visibility = in.visibility; s.visibilityTaps && visibility)
            launchSameLitTaps(b.acceptMask.data(), b.previousPixel.data(), visibility,
                              t.hasHistory() ? b.lit[prev].data() : nullptr, b.lit[cur].data(),
                              t.width, t.height, st);
        frame_.mark("fit");

        if (s.adaptiveHistory)
            launchHistoryChange(b.changeTiles.data(), b.change.data(), t.width, t.height,
                                s.historyChangeThreshold, s.historyChangeGain, st);
        launchAccumulateFitted(fittedAccumulation(ctx, in, b), b.remodulated.data(), st);
        frame_.mark("accumulate_fitted");

        const TaaInputs taa =
            taaInputs(b.remodulated.data(), b.output[prev].data(), b.previousPixel.data(), t.width,
                      t.height, s, b.acceptMask.data());
        launchTaa(taa, b.ycocg.data(), b.output[cur].data(), s.taa && t.hasHistory(), st);
        frame_.mark("taa");

        if (!frame_.onDevice()) b.output[cur].download(host_.output[cur], st);
        unsigned long long counts[DeviceFrame::kCounters];
        frame_.finish(b.counters.data(), times, counts);
        return {int64_t(counts[0]), int64_t(counts[1])};
    }

    /// In the memory the frame's buffers were in.
    ImageView output(int slot) const override {
        return frame_.onDevice() ? deviceView(b_.output[slot]) : view(host_.output[slot]);
    }

    void captureDebugOnDevice(const TemporalHistory& t) override {
        const cudaStream_t st = frame_.get();
        b_.accumulatedNoisy[t.cur].download(host_.noisy, st);
        b_.fitted.download(host_.fitted, st);
        b_.historyLength[t.cur].download(host_.historyLength, st);
        b_.acceptMask.download(host_.accept, st);
        frame_.synchronize();
        widenToFloat(host_.historyLength, host_.historyLengthF);
        widenToFloat(host_.accept, host_.acceptF);
    }

    DebugBuffers debug(const TemporalHistory&) const override {
        return {view(host_.noisy), view(host_.fitted), view(host_.historyLengthF),
                view(host_.acceptF)};
    }

  private:
    Buffers b_;
    HostCopies host_;
    FitPlan plan_;
    DeviceFrame frame_; ///< last (device_frame.h)
};

} // namespace

template <> std::unique_ptr<BmfrPasses> makePasses<BmfrSettings>(int device) {
    return makeOnDevice<BmfrSettings, CudaBmfrPasses>(device);
}

} // namespace bmfr::cuda
