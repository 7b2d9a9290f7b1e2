// The CPU backend's WALR: the reference's per-pixel preprocess, solve and postprocess, and the
// eight-wide a-trous iterations, where nearly all of WALR's time goes.
#include "backend/cpu/walr/cpu_walr_atrous.h"
#include "backend/reference/walr/reference_walr_stages.h"
#include "core/stopwatch.h"

namespace bmfr::cpu {

namespace {

class CpuWalrPasses final : public HostWalrPasses {
  public:
    int64_t run(const WalrPassContext& ctx, StageTimes& times) override {
        const WalrSettings& s = ctx.settings;
        Stopwatch clock;
        const int64_t bad = reference::walrPreprocess(ctx, buffers);
        times.add("preprocess", clock.lap());
        if (s.solver == WalrSolver::Refwlr) {
            reference::walrSpatialRefwlr(ctx, buffers);
        } else {
            const EdgeGuide g = buffers.guide(ctx);
            planes_.fill(ctx.pool, g);
            for (int t = 0; t < s.iterations; ++t)
                walrAtrousIteration(ctx.pool, g, planes_, buffers.level(ctx, t, s.sampleWeights));
            buffers.lastAverages = s.iterations % 2;
            reference::walrSolve(ctx, buffers);
        }
        times.add("spatial", clock.lap());
        reference::walrPostprocess(ctx, buffers);
        times.add("postprocess", clock.lap());
        return bad;
    }

  private:
    EdgePlanes planes_;
};

} // namespace

std::unique_ptr<WalrPasses> makeWalrPasses() {
    return std::make_unique<CpuWalrPasses>();
}

} // namespace bmfr::cpu
