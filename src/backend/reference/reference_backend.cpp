#include "backend/reference/reference_passes.h"
#include <chrono>

namespace bmfr::reference {

namespace {

class ReferencePasses final : public BmfrPasses {
  public:
    void allocate(int w, int h, const Settings& s, int threads) override {
        Buffers& b = b_;
        for (int k = 0; k < 2; ++k) {
            b.normal[k].resize(w, h, 3);
            b.position[k].resize(w, h, 3);
            b.accumulatedNoisy[k].resize(w, h, 3);
            b.historyLength[k].resize(w, h, 1);
            b.accumulatedFitted[k].resize(w, h, 3);
            b.output[k].resize(w, h, 3);
        }
        b.previousPixel.resize(w, h, 2);
        b.acceptMask.resize(w, h, 1);
        b.fitted.resize(w, h, 3);
        b.remodulated.resize(w, h, 3);
        b.ycocg.resize(w, h, 3);
        b.historyLengthF.resize(w, h, 1);
        b.acceptMaskF.resize(w, h, 1);
        const int W = s.blockSize * s.blockSize, M = int(s.features.size());
        b.scratch.resize(size_t(threads));
        for (FitScratch& sc : b.scratch) {
            sc.clean.assign(size_t(M) * W, 0.0f);
            sc.work.assign(size_t(M + 3) * W, 0.0f);
            sc.sum.assign(size_t(3) * W, 0.0f);
            sc.soa.assign(size_t(6 + 16) * W, 0.0f);
            sc.imageIndex.assign(size_t(W), -1);
        }
    }

    InputCounters run(const BmfrPassContext& ctx, StageTimes& times) override {
        using Clock = std::chrono::steady_clock;
        auto ms = [](Clock::time_point a, Clock::time_point b) {
            return std::chrono::duration<double, std::milli>(b - a).count();
        };
        const BmfrTimeline& t = ctx.timeline;
        Buffers& b = b_;
        auto t0 = Clock::now();
        InputCounters counters = accumulateNoisy(ctx, b);
        auto t1 = Clock::now();
        fitBlocks(ctx, b);
        auto t2 = Clock::now();
        accumulateFitted(ctx, b);
        auto t3 = Clock::now();
        temporalAntiAliasing(ctx.pool, b.remodulated.data(), b.output[1 - t.cur].data(),
                             b.previousPixel.data(), b.ycocg.data(), b.output[t.cur].data(),
                             t.width, t.height, ctx.settings.taaBlendAlpha,
                             ctx.settings.stages.taa && t.hasHistory);
        auto t4 = Clock::now();
        times.add("accumulate", ms(t0, t1));
        times.add("fit", ms(t1, t2));
        times.add("accumulate_fitted", ms(t2, t3));
        times.add("taa", ms(t3, t4));
        return counters;
    }

    ImageView output(int slot) const override { return view(b_.output[slot]); }

    void captureDebug(const BmfrTimeline& t) override {
        for (long i = 0; i < b_.historyLengthF.pixelCount(); ++i) {
            b_.historyLengthF.data()[i] = b_.historyLength[t.cur].data()[i];
            b_.acceptMaskF.data()[i] = b_.acceptMask.data()[i];
        }
    }

    DebugBuffers debug(const BmfrTimeline& t) const override {
        return {view(b_.accumulatedNoisy[t.cur]), view(b_.fitted), view(b_.historyLengthF),
                view(b_.acceptMaskF)};
    }

  private:
    Buffers b_;
};

} // namespace

} // namespace bmfr::reference

namespace bmfr {
std::unique_ptr<BmfrPasses> makeReferencePasses() {
    return std::make_unique<reference::ReferencePasses>();
}
} // namespace bmfr
