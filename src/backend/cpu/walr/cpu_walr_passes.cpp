// The CPU backend's WALR: the reference's per-pixel preprocess and postprocess, and the
// eight-wide spatial filter, where nearly all of WALR's time goes.
#include "backend/backend_registry.h"
#include "backend/cpu/walr/cpu_walr_spatial.h"
#include "backend/reference/walr/reference_walr_stages.h"

namespace bmfr::cpu {

namespace {

class CpuWalrPasses final : public reference::HostWalrPipeline {
  public:
    void allocate(int w, int h, const WalrSettings&, int) override {
        buffers.interleaved = true;
        buffers.allocate(w, h);
        planes_.allocate(w, h);
    }

  protected:
    void atrousAndSolve(const WalrPassContext& ctx) override {
        const WalrSettings& s = ctx.settings;
        const EdgeGuide g = buffers.guide(ctx);
        planes_.fill(ctx.pool, g);
        const int iterations = walrIterations(s, g.width, g.height);
        for (int t = 0; t < iterations; ++t)
            walrAtrousIteration(ctx.pool, g, planes_, buffers.level(ctx, t, s.sampleWeights));
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
