// Mara 2017's reference passes: one parallel loop over the stage bodies per stage.
#include "backend/backend_registry.h"
#include "backend/reference/mara2017/reference_mara_stages.h"
#include "backend/reference/reference_taa.h"
#include "core/stopwatch.h"
#include <algorithm>
#include <atomic>

namespace bmfr::reference {

int64_t HostMaraPipeline::matteTemporal(const MaraPassContext& ctx, const MaraFrame& f) {
    std::atomic<int64_t> nonFinite{0};
    ctx.pool.parallelFor(f.height, 4, [&](long y0, long y1) {
        int64_t bad = 0;
        for (long i = y0 * f.width; i < y1 * f.width; ++i) maraInputPixel(f, i, bad);
        nonFinite += bad;
    });
    ctx.pool.forEachPixel(f.width, f.height, 4,
                          [&](int x, int y) { maraMatteTemporalPixel(f, x, y); });
    return nonFinite.load();
}

void HostMaraPipeline::preBilateral(const MaraPassContext& ctx, const MaraFrame& f) {
    ctx.pool.forEachPixel(f.width, f.height, 2,
                          [&](int x, int y) { maraPreBilateralPixel(f, x, y); });
}

void HostMaraPipeline::disocclusion(const MaraPassContext& ctx, const MaraFrame& f) {
    ctx.pool.forEachPixel(f.width, f.height, 4, [&](int x, int y) { maraRowMinPixel(f, x, y); });
    ctx.pool.forEachPixel(f.width, f.height, 4, [&](int x, int y) { maraColumnMinPixel(f, x, y); });
}

void HostMaraPipeline::median(const MaraPassContext& ctx, const MaraFrame& f) {
    ctx.pool.forEachPixel(f.width, f.height, 4, [&](int x, int y) { maraMedianPixel(f, x, y); });
}

void HostMaraPipeline::matteBilateral(const MaraPassContext& ctx, const MaraFrame& f,
                                      const float* src) {
    ctx.pool.forEachPixel(f.width, f.height, 2,
                          [&](int x, int y) { maraFinalBilateralPixel(f, src, x, y); });
}

void HostMaraPipeline::glossyTemporal(const MaraPassContext& ctx, const MaraFrame& f) {
    ctx.pool.forEachPixel(f.width, f.height, 4,
                          [&](int x, int y) { maraGlossyTemporalPixel(f, x, y); });
}

void HostMaraPipeline::glossyBilateral(const MaraPassContext& ctx, const MaraFrame& f) {
    ctx.pool.forEachPixel(f.width, f.height, 4, [&](int x, int y) {
        maraGlossyPassPixel(f, f.glossyTemporal, f.glossyRow, x, y, 1, 0);
    });
    ctx.pool.forEachPixel(f.width, f.height, 4, [&](int x, int y) {
        maraGlossyPassPixel(f, f.glossyRow, f.glossyOut, x, y, 0, 1);
    });
}

void HostMaraPipeline::compose(const MaraPassContext& ctx, const MaraFrame& f) {
    ctx.pool.parallelFor(f.height, 8, [&](long y0, long y1) {
        for (long i = y0 * f.width; i < y1 * f.width; ++i) maraComposePixel(f, i);
    });
}

PassCounters HostMaraPipeline::run(const MaraPassContext& ctx, StageTimes& times) {
    const Mara2017Settings& s = ctx.settings;
    const TemporalHistory& h = ctx.history;
    const MaraFrame f = buffers.frame(ctx);
    const long n = long(f.width) * f.height;
    Stopwatch clock;
    const int64_t bad = matteTemporal(ctx, f);
    const int64_t discarded = countDiscarded(ctx.pool, f.accept, n, h.hasHistory());
    times.add("matte temporal", clock.lap());
    if (s.preBilateral)
        preBilateral(ctx, f);
    else
        std::copy(f.temporal, f.temporal + 3 * n, f.matteHistory);
    times.add("pre-bilateral", clock.lap());
    disocclusion(ctx, f);
    times.add("disocclusion", clock.lap());
    if (s.median) median(ctx, f);
    times.add("firefly median", clock.lap());
    matteBilateral(ctx, f, s.median ? f.median : f.temporal);
    times.add("matte bilateral", clock.lap());
    if (f.glossy) {
        glossyTemporal(ctx, f);
        times.add("glossy temporal", clock.lap());
        glossyBilateral(ctx, f);
        times.add("glossy bilateral", clock.lap());
    }
    if (s.taa && h.hasHistory()) {
        compose(ctx, f);
        taaPass(ctx.pool, buffers.taaInputs(ctx), buffers.ycocg.data(),
                buffers.output[h.cur].data(), true);
    } else { // straight into the output, not through a copy
        MaraFrame out = f;
        out.composed = buffers.output[h.cur].data();
        compose(ctx, out);
    }
    times.add("compose", clock.lap());
    return {bad, discarded};
}

namespace {

class ReferenceMaraPasses final : public HostMaraPipeline {};

} // namespace

template <> std::unique_ptr<MaraPasses> makePasses<Mara2017Settings>() {
    return std::make_unique<ReferenceMaraPasses>();
}

} // namespace bmfr::reference
