// The CPU backend's SVGF: eight-wide accumulation (cpu_svgf_accumulate.h), variance estimate
// (cpu_svgf_variance.h), a-trous levels (cpu_svgf_atrous.h) and re-modulation from the last
// level's planes, and the TAA shared with BMFR.
#include "backend/backend_registry.h"
#include "backend/cpu/cpu_taa.h"
#include "backend/cpu/modulation8.h"
#include "backend/cpu/svgf/cpu_svgf_accumulate.h"
#include "backend/cpu/svgf/cpu_svgf_atrous.h"
#include "backend/cpu/svgf/cpu_svgf_variance.h"
#include "backend/cpu/svgf/cpu_svgf_weights.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/stopwatch.h"
#include <algorithm>

namespace bmfr::cpu {

namespace {

/// reference::svgfRemodulate's pixels from the last level's R, G and B planes (rows `pitch`
/// floats apart), eight at a time, bit for bit.
BMFR_SIMD_DISPATCH(void, remodulateRows,
                   (const float* const rgb[3], long pitch, const InputPlanes& in,
                    float albedoEpsilon, int width, float* out, long y0, long y1),
                   (rgb, pitch, in, albedoEpsilon, width, out, y0, y1)) {
    using namespace simd;
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < width; x += 8) {
            const int n = std::min(8, width - x);
            const long i = y * width + x;
            f8 c[3];
            for (int k = 0; k < 3; ++k) c[k] = loadFirst(rgb[k] + y * pitch + x, n);
            remodulate8(c, in, i, n, true, albedoEpsilon);
            storeXyz8(out + 3 * i, n, c);
        }
}

class CpuSvgfPasses final : public HostSvgfPasses {
  public:
    void allocate(int w, int h, const SvgfSettings& s, int threads) override {
        HostSvgfPasses::allocate(w, h, s, threads);
        taaScratch_.assign(taaScratchFloats(w, h), 0.0f);
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
            taa(ctx, times);
            return counters;
        }
        const PassCounters counters =
            reference::svgfAccumulate(ctx, buffers, times, svgfAccumulateRows, false);
        Stopwatch clock;
        // The variance estimate writes the levels' first planes (and their guides, the depth
        // gradient made there).
        const SvgfFrame f = buffers.frame(ctx);
        const SvgfFirstLevel first = atrous_.firstLevel(h.width, h.height, ctx.settings);
        ctx.pool.parallelFor(h.height, 4, [&](long y0, long y1) {
            svgfVarianceRows(f, ctx.settings, y0, y1, buffers.filtered[0].data(),
                             buffers.variance.data(), &first);
        });
        times.add("variance", clock.lap());
        buffers.outputLevel = atrous_.run(ctx.pool, ctx.settings, buffers.color[h.cur].data());
        const float* const last[3] = {atrous_.level(buffers.outputLevel, 0),
                                      atrous_.level(buffers.outputLevel, 1),
                                      atrous_.level(buffers.outputLevel, 2)};
        ctx.pool.parallelFor(h.height, 8, [&](long y0, long y1) {
            remodulateRows(last, atrous_.pitch(), ctx.input, ctx.settings.albedoEpsilon, h.width,
                           buffers.remodulated.data(), y0, y1);
        });
        times.add("atrous", clock.lap());
        taa(ctx, times);
        return counters;
    }

    void captureDebug(const TemporalHistory& h) override {
        if (levelsInPlanes_)
            atrous_.copyLevel(buffers.outputLevel, buffers.filtered[buffers.outputLevel].data());
        HostSvgfPasses::captureDebug(h);
    }

  private:
    void taa(const SvgfPassContext& ctx, StageTimes& times) {
        const TemporalHistory& h = ctx.history;
        Stopwatch clock;
        temporalAntiAliasing(ctx.pool, buffers.remodulated.data(), buffers.output[1 - h.cur].data(),
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
