// Mara 2017's reference passes: its stages (filters/mara2017/mara_stage_loops.h) on the host's
// threads.
#include "backend/backend_registry.h"
#include "backend/reference/mara2017/reference_mara_stages.h"
#include "backend/reference/reference_taa.h"
#include "core/stopwatch.h"
#include "filters/mara2017/mara_stage_loops.h"
#include <algorithm>

namespace bmfr::reference {

int64_t HostMaraPipeline::matteTemporal(const MaraPassContext& ctx, const MaraFrame& f) {
    unsigned long long nonFinite = 0;
    maraMatteTemporalStage(HostExecutor{ctx.pool}, f, FrameCounter{&nonFinite});
    return int64_t(nonFinite);
}

void HostMaraPipeline::preBilateral(const MaraPassContext& ctx, const MaraFrame& f) {
    maraPreBilateralStage(HostExecutor{ctx.pool}, f);
}

void HostMaraPipeline::disocclusion(const MaraPassContext& ctx, const MaraFrame& f) {
    maraDisocclusionStage(HostExecutor{ctx.pool}, f);
}

void HostMaraPipeline::median(const MaraPassContext& ctx, const MaraFrame& f) {
    maraMedianStage(HostExecutor{ctx.pool}, f);
}

void HostMaraPipeline::matteBilateral(const MaraPassContext& ctx, const MaraFrame& f,
                                      const float* src) {
    maraMatteBilateralStage(HostExecutor{ctx.pool}, f, src);
}

void HostMaraPipeline::glossyTemporal(const MaraPassContext& ctx, const MaraFrame& f) {
    maraGlossyTemporalStage(HostExecutor{ctx.pool}, f);
}

void HostMaraPipeline::glossyBilateral(const MaraPassContext& ctx, const MaraFrame& f) {
    maraGlossyBilateralStage(HostExecutor{ctx.pool}, f);
}

void HostMaraPipeline::compose(const MaraPassContext& ctx, const MaraFrame& f) {
    maraComposeStage(HostExecutor{ctx.pool}, f);
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
