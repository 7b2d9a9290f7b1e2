// The CPU backend's WALR: the preprocess and postprocess (cpu_walr_temporal.h) and the spatial
// filter (cpu_walr_spatial.h), eight pixels at a time.
#include "backend/backend_registry.h"
#include "backend/cpu/walr/cpu_walr_spatial.h"
#include "backend/cpu/walr/cpu_walr_temporal.h"
#include "backend/reference/walr/reference_walr_stages.h"
#include <atomic>

namespace bmfr::cpu {

namespace {

class CpuWalrPasses final : public reference::HostWalrPipeline {
  public:
    void allocate(int w, int h, const WalrSettings& s, int) override {
        buffers.interleaved = true;
        buffers.allocate(w, h);
        planes_.allocate(w, h, walrSteppedTrace(s));
    }

  protected:
    int64_t preprocess(const WalrPassContext& ctx) override {
        const WalrFrame f = buffers.frame(ctx);
        std::atomic<int64_t> nonFinite{0};
        ctx.pool.parallelFor(f.height, 4,
                             [&](long y0, long y1) { nonFinite += walrInputRows(f, y0, y1); });
        float* level0 = buffers.averages[0].data();
        ctx.pool.parallelFor(f.height, 4,
                             [&](long y0, long y1) { walrAccumulateRows(f, y0, y1, level0); });
        return nonFinite.load();
    }

    void postprocess(const WalrPassContext& ctx) override {
        const WalrPost p = buffers.postInputs(ctx);
        ctx.pool.parallelFor(p.height, 4, [&](long y0, long y1) { walrPostRows(p, y0, y1); });
    }

    void atrousAndSolve(const WalrPassContext& ctx) override {
        const WalrSettings& s = ctx.settings;
        const EdgeGuide g = buffers.guide(ctx);
        planes_.fill(ctx.pool, g);
        const int iterations = walrIterations(s, g.width, g.height);
        for (int t = 0; t < iterations; ++t)
            walrAtrousIteration(ctx.pool, g, planes_, buffers.level(ctx, t, s.sampleWeights),
                                t + 1 == iterations);
        buffers.lastAverages = iterations % 2;
        walrSolveImage(ctx.pool, g.width, g.height, buffers.averages[buffers.lastAverages].data(),
                       buffers.features.data(), s.pivotEpsilon, buffers.spatial.data());
    }

  private:
    EdgePlanes planes_;
};

} // namespace

template <> std::unique_ptr<WalrPasses> makePasses<WalrSettings>() {
    return std::make_unique<CpuWalrPasses>();
}

} // namespace bmfr::cpu
