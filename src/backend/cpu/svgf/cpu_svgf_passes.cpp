// The CPU backend's SVGF: the reference's re-modulation, with eight-wide accumulation
// (cpu_svgf_accumulate.h), variance estimate (cpu_svgf_variance.h), a-trous levels
// (cpu_svgf_atrous.h) and the TAA shared with BMFR.
#include "backend/backend_registry.h"
#include "backend/cpu/cpu_taa.h"
#include "backend/cpu/svgf/cpu_svgf_accumulate.h"
#include "backend/cpu/svgf/cpu_svgf_atrous.h"
#include "backend/cpu/svgf/cpu_svgf_variance.h"
#include "backend/cpu/svgf/cpu_svgf_weights.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/stopwatch.h"

namespace bmfr::cpu {

namespace {

class CpuSvgfPasses final : public HostSvgfPasses {
  public:
    void allocate(int w, int h, const SvgfSettings& s, int threads) override {
        HostSvgfPasses::allocate(w, h, s, threads);
        taaScratch_.assign(taaScratchFloats(w, h), 0.0f);
        atrous_.reserve(w, h, s);
    }
    PassCounters run(const SvgfPassContext& ctx, StageTimes& times) override {
        const PassCounters counters = reference::svgfAccumulateAndVariance(
            ctx, buffers, times, svgfAccumulateRows,
            cpuNormalPowerSupports(ctx.settings) ? svgfVarianceRows
                                                 : reference::svgfVariancePixels);
        const TemporalHistory& h = ctx.history;
        Stopwatch clock;
        if (cpuNormalPowerSupports(ctx.settings)) {
            float* const filtered[2] = {buffers.filtered[0].data(), buffers.filtered[1].data()};
            buffers.outputLevel =
                atrous_.run(ctx.pool, ctx.settings, reference::atrousGuides(ctx, buffers), filtered,
                            buffers.color[h.cur].data());
        } else {
            reference::svgfAtrousLevels(ctx, buffers);
        }
        reference::svgfRemodulate(ctx, buffers);
        times.add("atrous", clock.lap());
        temporalAntiAliasing(ctx.pool, buffers.remodulated.data(), buffers.output[1 - h.cur].data(),
                             buffers.previousPixel.data(), taaScratch_.data(),
                             buffers.output[h.cur].data(), h.width, h.height,
                             taaBlend(ctx.settings), ctx.settings.taa && h.hasHistory(),
                             ctx.settings.taaSameSurface ? buffers.accept.data() : nullptr,
                             taaSpaceOf(ctx.settings));
        times.add("taa", clock.lap());
        return counters;
    }

  private:
    std::vector<float> taaScratch_;
    CpuAtrous atrous_;
};

} // namespace

template <> std::unique_ptr<SvgfPasses> makePasses<SvgfSettings>() {
    return std::make_unique<CpuSvgfPasses>();
}

} // namespace bmfr::cpu
