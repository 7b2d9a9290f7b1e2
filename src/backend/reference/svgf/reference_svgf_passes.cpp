// SVGF's reference passes: the accumulation and variance by rows (the CPU backend's hooks), the
// other stages (filters/svgf/svgf_stage_loops.h) on the host's threads, then the shared TAA.
#include "backend/backend_registry.h"
#include "backend/reference/reference_taa.h"
#include "backend/reference/svgf/reference_svgf_stages.h"
#include "core/stopwatch.h"
#include "filters/svgf/svgf_stage_loops.h"
#include <atomic>

namespace bmfr::reference {

int64_t svgfAccumulatePixels(const SvgfFrame& f, long y0, long y1) {
    int64_t bad = 0;
    for (long i = y0 * f.width; i < y1 * f.width; ++i) svgfAccumulatePixel(f, i, bad);
    return bad;
}

void svgfVariancePixels(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1,
                        float* filtered, float* variance) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < f.width; ++x) svgfVariancePixel(f, s, x, int(y), filtered, variance);
}

PassCounters svgfAccumulate(const SvgfPassContext& ctx, SvgfBuffers& b, StageTimes& times,
                            SvgfAccumulateRows rows, bool depthGradient) {
    const TemporalHistory& h = ctx.history;
    const SvgfFrame f = b.frame(ctx);
    Stopwatch clock;
    std::atomic<int64_t> nonFinite{0};
    ctx.pool.parallelFor(h.height, 4, [&](long y0, long y1) { nonFinite += rows(f, y0, y1); });
    if (depthGradient) svgfDepthGradientStage(HostExecutor{ctx.pool}, f);
    const int64_t discarded =
        countDiscarded(ctx.pool, f.accept, b.accept.pixelCount(), h.hasHistory());
    times.add("accumulate", clock.lap());
    return {nonFinite.load(), discarded};
}

PassCounters svgfAccumulateAndVariance(const SvgfPassContext& ctx, SvgfBuffers& b,
                                       StageTimes& times, SvgfAccumulateRows rows,
                                       SvgfVarianceRows varianceRows) {
    const PassCounters counters = svgfAccumulate(ctx, b, times, rows);
    const SvgfFrame f = b.frame(ctx);
    Stopwatch clock;
    ctx.pool.parallelFor(ctx.history.height, 4, [&](long y0, long y1) {
        varianceRows(f, ctx.settings, y0, y1, b.filtered[0].data(), b.variance.data());
    });
    times.add("variance", clock.lap());
    return counters;
}

AtrousLevel atrousGuides(const SvgfPassContext& ctx, SvgfBuffers& b) {
    const int cur = ctx.history.cur;
    return {nullptr,
            nullptr,
            b.normal[cur].data(),
            b.depth.data(),
            b.depthGradient.data(),
            b.historyLength[cur].data(),
            ctx.history.width,
            ctx.history.height};
}

void svgfAtrousLevels(const SvgfPassContext& ctx, SvgfBuffers& b) {
    b.outputLevel =
        svgfAtrousLevelsStage(HostExecutor{ctx.pool}, ctx.settings, atrousGuides(ctx, b),
                              b.filtered, b.color[ctx.history.cur].data());
}

void svgfRemodulate(const SvgfPassContext& ctx, SvgfBuffers& b) {
    svgfRemodulateStage(HostExecutor{ctx.pool}, b.filtered[b.outputLevel].data(), ctx.input,
                        ctx.settings.albedoEpsilon, b.remodulated.data());
}

PassCounters svgfStagesBeforeTaa(const SvgfPassContext& ctx, SvgfBuffers& b, StageTimes& times) {
    const PassCounters counters = svgfAccumulateAndVariance(ctx, b, times);
    Stopwatch clock;
    svgfAtrousLevels(ctx, b);
    svgfRemodulate(ctx, b);
    times.add("atrous", clock.lap());
    return counters;
}

namespace {

class ReferenceSvgfPasses final : public HostSvgfPasses {
  public:
    void allocate(int w, int h, const SvgfSettings& s, int threads) override {
        HostSvgfPasses::allocate(w, h, s, threads);
        ycocg_.resize(w, h, 3);
    }
    PassCounters run(const SvgfPassContext& ctx, StageTimes& times) override {
        const PassCounters counters = svgfStagesBeforeTaa(ctx, buffers, times);
        const TemporalHistory& h = ctx.history;
        Stopwatch clock;
        const TaaInputs taa = taaInputs(
            buffers.remodulated.data(), buffers.output[1 - h.cur].data(),
            buffers.previousPixel.data(), h.width, h.height, ctx.settings, buffers.accept.data());
        taaPass(ctx.pool, taa, ycocg_.data(), buffers.output[h.cur].data(),
                ctx.settings.taa && h.hasHistory());
        times.add("taa", clock.lap());
        return counters;
    }

  private:
    ImageF ycocg_;
};

} // namespace

template <> std::unique_ptr<SvgfPasses> makePasses<SvgfSettings>() {
    return std::make_unique<ReferenceSvgfPasses>();
}

} // namespace bmfr::reference
