// The CPU backend's SVGF: the reference's scalar stages up to TAA (they are branchy per-tap
// loops that gain little from eight-wide code yet), then the eight-wide TAA shared with BMFR.
#include "backend/cpu/cpu_taa.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/stopwatch.h"

namespace bmfr::cpu {

namespace {

class CpuSvgfPasses final : public SvgfPasses {
  public:
    void allocate(int w, int h) override {
        b_.allocate(w, h);
        taaScratch_.assign(taaScratchFloats(w, h), 0.0f);
    }
    int64_t run(const SvgfPassContext& ctx, StageTimes& times) override {
        const int64_t bad = reference::svgfStagesBeforeTaa(ctx, b_, times);
        const TemporalHistory& h = ctx.history;
        Stopwatch clock;
        temporalAntiAliasing(ctx.pool, b_.remodulated.data(), b_.output[1 - h.cur].data(),
                             b_.previousPixel.data(), taaScratch_.data(), b_.output[h.cur].data(),
                             h.width, h.height, ctx.settings.taaBlendAlpha,
                             ctx.settings.taa && h.hasHistory());
        times.add("taa", clock.lap());
        return bad;
    }
    ImageView output(int slot) const override { return view(b_.output[slot]); }
    ImageView variance() const override { return view(b_.variance); }
    void captureDebug(int cur) override { b_.captureDebug(cur); }
    DebugBuffers debug(int cur) const override { return b_.debug(cur); }

  private:
    SvgfBuffers b_;
    std::vector<float> taaScratch_;
};

} // namespace

std::unique_ptr<SvgfPasses> makeSvgfPasses() {
    return std::make_unique<CpuSvgfPasses>();
}

} // namespace bmfr::cpu
