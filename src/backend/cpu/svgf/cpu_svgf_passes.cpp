// The CPU backend's SVGF: eight-wide accumulation (cpu_svgf_accumulate.h), variance estimate
// (cpu_svgf_variance.h), a-trous levels (cpu_svgf_atrous.h), and the TAA shared with BMFR,
// which re-modulates the last level's planes as it reads them.
#include "backend/backend_registry.h"
#include "backend/cpu/cpu_taa.h"
#include "backend/cpu/svgf/cpu_svgf_accumulate.h"
#include "backend/cpu/svgf/cpu_svgf_atrous.h"
#include "backend/cpu/svgf/cpu_svgf_variance.h"
#include "backend/cpu/svgf/cpu_svgf_weights.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/stopwatch.h"
#include <algorithm>

namespace bmfr::cpu {

namespace {

class CpuSvgfPasses final : public HostSvgfPasses {
  public:
    void allocate(int w, int h, const SvgfSettings& s, int threads) override {
        HostSvgfPasses::allocate(w, h, s, threads);
        taaScratch_.assign(taaScratchFloats(w, threads), 0.0f);
        atrous_.reserve(w, h, s);
    }
    PassCounters run(const SvgfPassContext& ctx, StageTimes& times) override {
        const TemporalHistory& h = ctx.history;
        levelsInPlanes_ = cpuNormalPowerSupports(ctx.settings);
        if (!levelsInPlanes_) { // the reference's variance estimate and levels
            const PassCounters counters = reference::svgfAccumulateAndVariance(
                ctx, buffers, times, svgfAccumulateRows, reference::svgfVariancePixels);
            Stopwatch clock;
            reference::svgfAtrousLevels(ctx, buffers);
            reference::svgfRemodulate(ctx, buffers);
            times.add("atrous", clock.lap());
            TaaCurrent current;
            current.rgb = buffers.remodulated.data();
            taa(ctx, current, times);
            return counters;
        }
        const PassCounters counters =
            reference::svgfAccumulate(ctx, buffers, times, svgfAccumulateRows, false);
        Stopwatch clock;
        // The variance estimate writes the levels' first planes (and their guides, the depth
        // gradient made there); its 7x7 estimate reads them.
        const SvgfFrame f = buffers.frame(ctx);
        const SvgfFirstLevel first = atrous_.firstLevel(h.width, h.height, ctx.settings);
        ctx.pool.parallelFor(h.height, 4,
                             [&](long y0, long y1) { svgfFirstLevelRows(f, first, y0, y1); });
        ctx.pool.parallelFor(h.height, 4, [&](long y0, long y1) {
            svgfVarianceRows(f, ctx.settings, first, y0, y1, buffers.variance.data());
        });
        times.add("variance", clock.lap());
        buffers.outputLevel = atrous_.run(ctx.pool, ctx.settings, buffers.color[h.cur].data());
        times.add("atrous", clock.lap());
        TaaCurrent current; // the last level, re-modulated as the TAA reads it
        for (int k = 0; k < 3; ++k) current.planes[k] = atrous_.level(buffers.outputLevel, k);
        current.pitch = atrous_.pitch();
        current.in = &ctx.input;
        current.albedoEpsilon = ctx.settings.albedoEpsilon;
        taa(ctx, current, times);
        return counters;
    }

    void captureDebug(const TemporalHistory& h) override {
        if (levelsInPlanes_)
            atrous_.copyLevel(buffers.outputLevel, buffers.filtered[buffers.outputLevel].data());
        HostSvgfPasses::captureDebug(h);
    }

  private:
    void taa(const SvgfPassContext& ctx, const TaaCurrent& current, StageTimes& times) {
        const TemporalHistory& h = ctx.history;
        Stopwatch clock;
        temporalAntiAliasing(ctx.pool, current, buffers.output[1 - h.cur].data(),
                             buffers.previousPixel.data(), taaScratch_.data(),
                             buffers.output[h.cur].data(), h.width, h.height,
                             taaBlend(ctx.settings), ctx.settings.taa && h.hasHistory(),
                             ctx.settings.taaSameSurface ? buffers.accept.data() : nullptr,
                             taaSpaceOf(ctx.settings));
        times.add("taa", clock.lap());
    }

    std::vector<float> taaScratch_;
    CpuAtrous atrous_;
    bool levelsInPlanes_ = false; ///< the last level is in atrous_'s planes, not in filtered[]
};

} // namespace

template <> std::unique_ptr<SvgfPasses> makePasses<SvgfSettings>() {
    return std::make_unique<CpuSvgfPasses>();
}

} // namespace bmfr::cpu
