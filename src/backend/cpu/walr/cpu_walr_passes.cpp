// The CPU backend's WALR: the reference's per-pixel preprocess and postprocess, and the
// eight-wide spatial filter, where nearly all of WALR's time goes.
#include "backend/cpu/walr/cpu_walr_spatial.h"
#include "backend/reference/walr/reference_walr_stages.h"
#include "core/stopwatch.h"

namespace bmfr::cpu {

namespace {

class CpuWalrPasses final : public HostWalrPasses {
  public:
    void allocate(int w, int h) override {
        buffers.interleaved = true;
        buffers.allocate(w, h);
    }
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
            walrSolveImage(ctx.pool, g.width, g.height,
                           buffers.averages[buffers.lastAverages].data(),
                           buffers.features.data(), s.pivotEpsilon, buffers.spatial.data());
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
