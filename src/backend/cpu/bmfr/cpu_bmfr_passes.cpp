// The CPU backend's BMFR: planes, phase I interleaved with the fit block row by block row, and
// phase III fused with TAA and with the taps dropped across emitter and shadow edges (see
// cpu_bmfr_buffers.h).
#include "backend/backend_registry.h"
#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/taa_rows.h"
#include "core/stopwatch.h"
#include "filters/bmfr/fitting_kernel.h"
#include "filters/bmfr/history_change.h"

namespace bmfr::cpu {

namespace {

class CpuBmfrPasses final : public BmfrPasses {
  public:
    void allocate(int w, int h, const BmfrSettings& s, int threads) override {
        const size_t n = size_t(w) * size_t(h);
        b_.width = w, b_.height = h;
        b_.stride = (n + 7) / 8 * 8 + 8; // an 8-float load at any pixel stays in its plane
        for (int k = 0; k < 2; ++k) {
            b_.position[k].assign(3, b_.stride, false);
            b_.normal[k].assign(3, b_.stride, s.halfHistory);
            b_.noisy[k].assign(4, b_.stride, s.halfHistory);
            b_.accumulatedFitted[k].assign(3, b_.stride, s.halfHistory);
            b_.output[k].assign(3 * n + 24, 0.0f);
            b_.tapClass[k].assign(s.excludeEmitters || s.visibilityTaps ? n + 8 : 0, 0);
            b_.emitterPixels[k] = 0;
        }
        b_.previousPixel.assign(2 * b_.stride, 0.0f);
        b_.acceptMask.assign(n + 8, 0);
        b_.resolvedAccept.assign(s.excludeEmitters ? n + 8 : 0, 0);
        b_.fitted.assign(3 * b_.stride, 0.0f);
        b_.fittedSecond.assign(s.secondGrid ? 3 * b_.stride : 0, 0.0f);
        b_.earlyRow.assign(size_t(h), 0);
        // The shifted grid has as many blocks as the frame's, whatever its offsets.
        const size_t gridBlocks = size_t(makeBlockGrid(w, h, s.blockSize, 0).blockCount());
        b_.secondPoor.assign(s.secondGrid ? gridBlocks : 0, 0);
        b_.secondBlocks.clear();
        b_.secondBlocks.reserve(s.secondGrid ? gridBlocks : 0);
        b_.change.assign(s.adaptiveHistory || s.excludeEmitters ? 2 * b_.stride : 0, 0.0f);
        b_.changeTiles.assign(s.adaptiveHistory ? size_t(changeTileFloats(w, h)) : 0, 0.0f);
        const size_t W = size_t(s.blockSize) * size_t(s.blockSize), M = s.features.size();
        b_.noise.assign(M * W, 0.0f);
        b_.scratch.resize(size_t(threads));
        for (Scratch& sc : b_.scratch) {
            sc.clean.assign(M * W, 0.0f);
            sc.work.assign((M + 3) * size_t(qrColumnStride(int(W))), 0.0f);
            sc.soa.assign((9 + InputPlanes::kMaxExtras) * W, 0.0f);
            sc.imageIndex.assign(W, -1);
            sc.ones.assign(size_t(s.blockSize) + 8, 1.0f);
            sc.rows.assign(3 * ResolvedRows::rowFloats(w), 0.0f);
            sc.mask.assign(W, 0);
            sc.histogram.assign(kMaskBuckets, 0);
            sc.lum.assign(W + 4 * 8, 0.0f); // gather8 reads up to W + 24
            sc.buckets.assign(W / kMaskStride + 8, 0);
        }
    }

    PassCounters run(const BmfrPassContext& ctx, StageTimes& times) override {
        // Phase I and the fit run interleaved; their wall time is split by the workers' time in
        // each (StageSplit).
        StageSplit split;
        const TemporalHistory& t = ctx.history;
        b_.emitterPixels[t.cur] = 0;
        fillRegularisationNoise(ctx.settings, t.frameIndex, b_.noise);
        TapFilter filter;
        PassCounters counters = accumulateAndFit(ctx, b_, split);
        Stopwatch clock;
        if (ctx.settings.secondGrid && ctx.settings.stages.fitting) {
            fitSecondGrid(ctx, b_);
            split.fitMs += clock.lap();
        }
        // Without an emitter in either frame no tap crosses an emitter's edge.
        filter.emitters = emitterExclusion(ctx.settings, ctx.input, nullptr).on &&
                          b_.emitterPixels[t.cur] + b_.emitterPixels[1 - t.cur] > 0;
        b_.acceptFiltered = filter.on();
        if (ctx.settings.adaptiveHistory) measureHistoryChange(ctx, b_);
        resolve(ctx, b_, filter);
        times.add("accumulate", split.accumulateMs);
        times.add("fit", split.fitMs);
        times.add("resolve", clock.lap());
        return counters;
    }

    ImageView output(int slot) const override {
        return ImageView{b_.output[slot].data(), b_.width, b_.height, 3};
    }

    void captureDebug(const TemporalHistory& t) override {
        // Sized on first use only: at 4K they would hold 265 MB nobody asked for.
        if (b_.debugNoisy.width != t.width || b_.debugNoisy.height != t.height) {
            b_.debugNoisy.resize(t.width, t.height, 3);
            b_.debugFitted.resize(t.width, t.height, 3);
            b_.debugLength.resize(t.width, t.height, 1);
            b_.debugAccept.resize(t.width, t.height, 1);
        }
        const long n = long(t.width) * t.height;
        for (long i = 0; i < n; ++i) {
            for (int c = 0; c < 3; ++c) {
                b_.debugNoisy.data()[3 * i + c] = b_.noisy[t.cur].at(c, size_t(i));
                b_.debugFitted.data()[3 * i + c] = b_.plane(b_.fitted, c)[i];
            }
            b_.debugLength.data()[i] = b_.noisy[t.cur].at(3, size_t(i));
            b_.debugAccept.data()[i] =
                (b_.acceptFiltered ? b_.resolvedAccept : b_.acceptMask)[size_t(i)];
        }
    }

    DebugBuffers debug(const TemporalHistory&) const override {
        return {view(b_.debugNoisy), view(b_.debugFitted), view(b_.debugLength),
                view(b_.debugAccept)};
    }

  private:
    Buffers b_;
};

} // namespace

} // namespace bmfr::cpu

namespace bmfr::cpu {
template <> std::unique_ptr<BmfrPasses> makePasses<BmfrSettings>() {
    return std::make_unique<CpuBmfrPasses>();
}
} // namespace bmfr::cpu
