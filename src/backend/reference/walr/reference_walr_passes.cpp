// WALR's reference passes: plain parallel loops over the filter's kernels, one per stage.
#include "backend/backend_registry.h"
#include "backend/reference/walr/reference_walr_stages.h"
#include "core/stopwatch.h"
#include "filters/walr/refwlr.h"
#include <atomic>

namespace bmfr::reference {

int64_t walrPreprocess(const WalrPassContext& ctx, WalrBuffers& b) {
    const TemporalHistory& h = ctx.history;
    const int w = h.width;
    const WalrFrame f = b.frame(ctx);
    std::atomic<int64_t> nonFinite{0};
    ctx.pool.parallelFor(h.height, 4, [&](long y0, long y1) {
        int64_t bad = 0;
        for (long i = y0 * w; i < y1 * w; ++i) walrInputPixel(f, i, bad);
        nonFinite += bad;
    });
    float* level0 = b.averages[0].data();
    const AverageLayout layout = b.layout();
    ctx.pool.forEachPixel(w, h.height, 4,
                          [&](int x, int y) { walrAccumulatePixel(f, x, y, level0, layout); });
    return nonFinite.load();
}

void walrSpatialRefwlr(const WalrPassContext& ctx, WalrBuffers& b) {
    const WalrSettings& s = ctx.settings;
    const EdgeGuide g = b.guide(ctx);
    int window = 1;
    const int iterations = walrIterations(s, g.width, g.height);
    for (int t = 0; t < iterations; ++t) window *= 3;
    const float* pre = b.pre[ctx.history.cur].data();
    ctx.pool.forEachPixel(g.width, g.height, 1, [&](int x, int y) {
        store3(b.spatial.data(), long(y) * g.width + x,
               refwlrPixel(g, pre, b.features.data(), window / 2, s.pivotEpsilon, x, y));
    });
}

void walrSolve(const WalrPassContext& ctx, WalrBuffers& b) {
    const float* planes = b.averages[b.lastAverages].data();
    const AverageLayout layout = b.layout();
    const float* f = b.features.data();
    const float eps = ctx.settings.pivotEpsilon;
    ctx.pool.parallelFor(ctx.history.height, 8, [&](long y0, long y1) {
        for (long i = y0 * ctx.history.width; i < y1 * ctx.history.width; ++i)
            store3(b.spatial.data(), i,
                   walrSolvePixel(planes, layout, i, {f[2 * i], f[2 * i + 1]}, eps));
    });
}

void walrPostprocess(const WalrPassContext& ctx, WalrBuffers& b) {
    const WalrPost p = b.postInputs(ctx);
    ctx.pool.forEachPixel(p.width, p.height, 4, [&](int x, int y) { walrPostPixel(p, x, y); });
}

PassCounters HostWalrPipeline::run(const WalrPassContext& ctx, StageTimes& times) {
    Stopwatch clock;
    const int64_t bad = preprocess(ctx);
    const int64_t discarded = countDiscarded(ctx.pool, buffers.accept.data(),
                                             buffers.accept.pixelCount(), ctx.history.hasHistory());
    times.add("preprocess", clock.lap());
    if (ctx.settings.solver == WalrSolver::Refwlr)
        walrSpatialRefwlr(ctx, buffers);
    else
        atrousAndSolve(ctx);
    times.add("spatial", clock.lap());
    postprocess(ctx);
    times.add("postprocess", clock.lap());
    return {bad, discarded};
}

namespace {

class ReferenceWalrPasses final : public HostWalrPipeline {
  public:
    void allocate(int w, int h, const WalrSettings& s, int threads) override {
        HostWalrPipeline::allocate(w, h, s, threads);
        trace_.resize(walrSteppedTrace(s) ? long(w) * h : 0);
    }

  protected:
    void atrousAndSolve(const WalrPassContext& ctx) override {
        const WalrSettings& s = ctx.settings;
        const EdgeGuide g = buffers.guide(ctx);
        const int iterations = walrIterations(s, g.width, g.height);
        for (int t = 0; t < iterations; ++t) {
            WalrLevel l = buffers.level(ctx, t, s.sampleWeights);
            if (g.stepped()) l.trace = trace_.at(t);
            ctx.pool.forEachPixel(g.width, g.height, 2,
                                  [&](int x, int y) { walrAtrousPixel(g, l, x, y); });
        }
        buffers.lastAverages = iterations % 2;
        walrSolve(ctx, buffers);
    }

  private:
    SteppedTraceBuffers trace_; ///< sized by allocate
};

} // namespace

template <> std::unique_ptr<WalrPasses> makePasses<WalrSettings>() {
    return std::make_unique<ReferenceWalrPasses>();
}

} // namespace bmfr::reference
