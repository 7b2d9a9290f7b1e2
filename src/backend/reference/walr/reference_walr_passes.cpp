// WALR's reference passes: its stages (filters/walr/walr_stages.h) on the host's threads.
#include "backend/backend_registry.h"
#include "backend/reference/walr/reference_walr_stages.h"
#include "core/stopwatch.h"
#include "filters/walr/walr_stages.h"

namespace bmfr::reference {

int64_t walrPreprocess(const WalrPassContext& ctx, WalrBuffers& b) {
    unsigned long long nonFinite = 0;
    walrPreprocessStage(HostExecutor{ctx.pool}, ctx, b, FrameCounter{&nonFinite});
    return int64_t(nonFinite);
}

void walrSpatialRefwlr(const WalrPassContext& ctx, WalrBuffers& b) {
    walrRefwlrStage(HostExecutor{ctx.pool}, ctx, b);
}

void walrSolve(const WalrPassContext& ctx, WalrBuffers& b) {
    walrSolveStage(HostExecutor{ctx.pool}, ctx, b);
}

void walrPostprocess(const WalrPassContext& ctx, WalrBuffers& b) {
    walrPostprocessStage(HostExecutor{ctx.pool}, ctx, b);
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
        walrAtrousStage(HostExecutor{ctx.pool}, ctx, buffers, trace_);
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
