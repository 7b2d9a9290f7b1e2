// The reference backend's BMFR: its stages (filters/bmfr/bmfr_stage_loops.h) on the host's
// threads, the fit block by block (fitting_kernel.h), and the shared TAA. The specification
// every other backend is held to.
#include "backend/reference/bmfr/reference_bmfr_passes.h"
#include "backend/backend_registry.h"
#include "backend/reference/bmfr/reference_householder.h"
#include "backend/reference/reference_taa.h"
#include "core/image.h"
#include "core/stopwatch.h"
#include "filters/bmfr/bmfr_images.h"
#include "filters/bmfr/bmfr_pass_setup.h"
#include "filters/bmfr/bmfr_passes.h"
#include "filters/bmfr/bmfr_stage_loops.h"
#include <algorithm>
#include <bmfr/error.h>
#include <type_traits>

namespace bmfr::reference {

namespace {

/// Per-thread scratch of the block fitter: one block's columns, contiguous.
struct FitScratch {
    std::vector<float> clean, work, sum, sources;
    std::vector<int> imageIndex;
    std::vector<uint8_t> mask;
    std::vector<int> histogram;
    BlockFitScratch view() {
        return {clean.data(),      work.data(), sum.data(),      sources.data(),
                imageIndex.data(), mask.data(), histogram.data()};
    }
};

/// Plain interleaved images (BmfrImages), with the fit's scratch and the debug copies.
template <class H> struct Buffers : BmfrImages<Image, H> {
    ImageF historyLengthF;           ///< debug copy of the history length as float
    ImageF acceptMaskF;              ///< debug copy of the accept mask as float
    ImageF noisyF;                   ///< debug copy of phase I's output as float (Half history)
    std::vector<float> changeTiles;  ///< adaptiveHistory: storeTileChange's record of each tile
    std::vector<FitScratch> scratch; ///< one per worker thread
    std::vector<float> noise;        ///< this frame's regularisation noise
};

template <class H> PassCounters accumulateNoisy(const BmfrPassContext& ctx, Buffers<H>& b) {
    unsigned long long nonFinite = 0, discarded = 0;
    bmfrAccumulateNoisyStage(HostExecutor{ctx.pool}, noisyAccumulation(ctx, ctx.input, b),
                             FrameCounter{&nonFinite}, FrameCounter{&discarded});
    return {int64_t(nonFinite), int64_t(discarded)};
}

/// Every block of a.grid.
template <class H> void fitGrid(const BmfrPassContext& ctx, Buffers<H>& b, const BlockFitOf<H>& a) {
    const BlockGrid& g = a.grid;
    const HouseholderSolver solve = householderSolver();
    ctx.pool.parallelFor(g.blockCount(), 1, [&](long b0, long b1) {
        const BlockFitScratch sc = b.scratch[size_t(ThreadPool::currentThreadIndex())].view();
        for (long k = b0; k < b1; ++k)
            fitBlock(a, int(k % g.blocksX), int(k / g.blocksX), sc, solve);
    });
}

template <class H> void fitBlocks(const BmfrPassContext& ctx, Buffers<H>& b) {
    const TemporalHistory& t = ctx.history;
    const BmfrSettings& s = ctx.settings;
    const HostExecutor e{ctx.pool};
    if (!s.stages.fitting) {
        bmfrUnfittedStage(e, b.accumulatedNoisy[t.cur].data(), b.fitted.data(),
                          long(b.fitted.pixels.size()));
        return;
    }
    fillRegularisationNoise(s, t.frameIndex, b.noise);
    const BlockFitOf<H> a = blockFit(ctx, ctx.input, b, s.features.data(), b.noise.data());
    fitGrid(ctx, b, a);
    if (s.secondGrid) {
        // Every block of the second grid: the spec; the CPU backend fits only those that own a
        // history-poor pixel, which gives the same pixels.
        BlockFitOf<H> second = a;
        second.grid = secondGrid(a.grid);
        second.fitted = b.fittedSecond.data(), second.emitters.bits = nullptr;
        fitGrid(ctx, b, second);
        bmfrBlendSecondFitStage(e, b.fitted.data(), b.fittedSecond.data(),
                                b.historyLength[t.cur].data(), long(t.width) * t.height);
    }
    if (!a.emitters.on) return;
    bmfrSameEmitterTapsStage(e, b.acceptMask.data(), b.previousPixel.data(),
                             b.emitter[1 - t.cur].data(), a.emitters.bits, t.width, t.height);
}

/// sameLitTaps over the accept mask (visibilityTaps, with a visibility buffer).
template <class H> void dropTapsAcrossShadowEdges(const BmfrPassContext& ctx, Buffers<H>& b) {
    const TemporalHistory& t = ctx.history;
    const float* visibility = ctx.input.visibility;
    if (!ctx.settings.visibilityTaps || !visibility) return;
    bmfrSameLitTapsStage(HostExecutor{ctx.pool}, b.acceptMask.data(), b.previousPixel.data(),
                         visibility, t.hasHistory() ? b.lit[1 - t.cur].data() : nullptr,
                         b.lit[t.cur].data(), t.width, t.height);
}

/// tileHistoryChange of every tile, stored with storeTileChange (adaptiveHistory).
template <class H> void measureHistoryChange(const BmfrPassContext& ctx, Buffers<H>& b) {
    const TemporalHistory& t = ctx.history;
    const BmfrSettings& s = ctx.settings;
    if (!s.adaptiveHistory) return;
    bmfrHistoryChangeStage(HostExecutor{ctx.pool}, b.changeTiles.data(), b.change.data(), t.width,
                           t.height, s.historyChangeThreshold, s.historyChangeGain);
}

template <class H> void accumulateFitted(const BmfrPassContext& ctx, Buffers<H>& b) {
    bmfrAccumulateFittedStage(HostExecutor{ctx.pool}, fittedAccumulation(ctx, ctx.input, b),
                              b.remodulated.data());
}

template <class H> class ReferenceBmfrPasses final : public BmfrPasses {
  public:
    void allocate(int w, int h, const BmfrSettings& s, int threads) override {
        if (std::is_same_v<H, Half> && !s.halfHistory)
            throw Error("internal error: history stored as half without halfHistory");
        Buffers<H>& b = b_;
        b.allocate(w, h, s);
        b.historyLengthF.resize(w, h, 1);
        b.acceptMaskF.resize(w, h, 1);
        b.noisyF.resize(std::is_same_v<H, float> ? 0 : w, std::is_same_v<H, float> ? 0 : h, 3);
        b.changeTiles.assign(s.adaptiveHistory ? size_t(changeTileFloats(w, h)) : 0, 0.0f);
        const size_t W = size_t(s.blockSize) * size_t(s.blockSize), M = s.features.size();
        b.noise.assign(M * W, 0.0f);
        b.scratch.resize(size_t(threads));
        for (FitScratch& sc : b.scratch) {
            sc.clean.assign(M * W, 0.0f);
            sc.work.assign((M + 3) * W, 0.0f);
            sc.sum.assign(3 * W, 0.0f);
            sc.sources.assign((6 + InputPlanes::kMaxExtras) * W, 0.0f);
            sc.imageIndex.assign(W, -1);
            sc.mask.assign(W, 0);
            sc.histogram.assign(kMaskBuckets, 0);
        }
    }

    PassCounters run(const BmfrPassContext& ctx, StageTimes& times) override {
        const TemporalHistory& t = ctx.history;
        Buffers<H>& b = b_;
        Stopwatch clock;
        const PassCounters counters = accumulateNoisy(ctx, b);
        times.add("accumulate", clock.lap());
        fitBlocks(ctx, b);
        dropTapsAcrossShadowEdges(ctx, b);
        times.add("fit", clock.lap());
        measureHistoryChange(ctx, b);
        accumulateFitted(ctx, b);
        times.add("accumulate_fitted", clock.lap());
        const TaaInputs taa =
            taaInputs(b.remodulated.data(), b.output[1 - t.cur].data(), b.previousPixel.data(),
                      t.width, t.height, ctx.settings, b.acceptMask.data());
        taaPass(ctx.pool, taa, b.ycocg.data(), b.output[t.cur].data(),
                ctx.settings.taa && t.hasHistory());
        times.add("taa", clock.lap());
        return counters;
    }

    ImageView output(int slot) const override { return view(b_.output[slot]); }

    void captureDebug(const TemporalHistory& t) override {
        for (long i = 0; i < b_.historyLengthF.pixelCount(); ++i) {
            b_.historyLengthF.data()[i] = b_.historyLength[t.cur].data()[i];
            b_.acceptMaskF.data()[i] = b_.acceptMask.data()[i];
        }
        if constexpr (!std::is_same_v<H, float>) {
            const H* noisy = b_.accumulatedNoisy[t.cur].data();
            std::copy(noisy, noisy + b_.noisyF.pixels.size(), b_.noisyF.data());
        }
    }

    DebugBuffers debug(const TemporalHistory& t) const override {
        const ImageF& noisy = noisyView(t);
        return {view(noisy), view(b_.fitted), view(b_.historyLengthF), view(b_.acceptMaskF)};
    }

  private:
    const ImageF& noisyView(const TemporalHistory& t) const {
        if constexpr (std::is_same_v<H, float>)
            return b_.accumulatedNoisy[t.cur];
        else
            return b_.noisyF;
    }
    Buffers<H> b_;
};

} // namespace

template <> std::unique_ptr<BmfrPasses> makePasses<BmfrSettings>() {
    return std::make_unique<ReferenceBmfrPasses<float>>();
}

std::unique_ptr<BmfrPasses> makeBmfrPassesStoringHalves() {
    return std::make_unique<ReferenceBmfrPasses<Half>>();
}

} // namespace bmfr::reference
