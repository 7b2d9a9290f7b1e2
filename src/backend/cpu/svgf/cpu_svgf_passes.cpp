// The CPU backend's SVGF: the reference's scalar stages up to TAA (they are branchy per-tap
// loops that gain little from eight-wide code yet), then the eight-wide TAA shared with BMFR.
#include "backend/backend_registry.h"
#include "backend/cpu/cpu_taa.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/stopwatch.h"

namespace bmfr::cpu {

namespace {

class CpuSvgfPasses final : public HostSvgfPasses {
  public:
    void allocate(int w, int h, const SvgfSettings& s, int threads) override {
        HostSvgfPasses::allocate(w, h, s, threads);
        taaScratch_.assign(taaScratchFloats(w, h), 0.0f);
    }
    PassCounters run(const SvgfPassContext& ctx, StageTimes& times) override {
        const PassCounters counters = reference::svgfStagesBeforeTaa(ctx, buffers, times);
        const TemporalHistory& h = ctx.history;
        Stopwatch clock;
        temporalAntiAliasing(ctx.pool, buffers.remodulated.data(), buffers.output[1 - h.cur].data(),
                             buffers.previousPixel.data(), taaScratch_.data(),
                             buffers.output[h.cur].data(), h.width, h.height,
                             ctx.settings.taaBlendAlpha, ctx.settings.taa && h.hasHistory(),
                             ctx.settings.taaSameSurface ? buffers.accept.data() : nullptr,
                             ctx.settings.taaToneMapped);
        times.add("taa", clock.lap());
        return counters;
    }

  private:
    std::vector<float> taaScratch_;
};

} // namespace

template <> std::unique_ptr<SvgfPasses> makePasses<SvgfSettings>() {
    return std::make_unique<CpuSvgfPasses>();
}

} // namespace bmfr::cpu
