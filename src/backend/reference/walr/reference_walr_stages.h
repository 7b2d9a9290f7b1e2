// WALR's reference stages, which the CPU backend reuses where it has nothing faster.
#pragma once
#include "filters/walr/walr_passes.h"

namespace bmfr::reference {

/// Passes 1a and 1b: inputs, reprojection, moving average and the level-0 averages (in
/// b.averages[0]); returns the count of non-finite inputs replaced.
int64_t walrPreprocess(const WalrPassContext& ctx, WalrBuffers& b);
/// REFWLR over the whole frame into b.spatial.
void walrSpatialRefwlr(const WalrPassContext& ctx, WalrBuffers& b);
/// The per-pixel solve of the last a-trous level (b.lastAverages) into b.spatial.
void walrSolve(const WalrPassContext& ctx, WalrBuffers& b);
/// Pass 3: the variance-clipped post blend and the composition into b.output.
void walrPostprocess(const WalrPassContext& ctx, WalrBuffers& b);

/// A host backend's WALR: these stages, timed, around the backend's own a-trous iterations and
/// solve (REFWLR when the settings ask for it).
class HostWalrPipeline : public HostPasses<WalrSettings, WalrBuffers> {
  public:
    PassCounters run(const WalrPassContext& ctx, StageTimes& times) final;

  protected:
    /// walrPreprocess, unless the backend has faster passes.
    virtual int64_t preprocess(const WalrPassContext& ctx) { return walrPreprocess(ctx, buffers); }
    /// walrPostprocess, unless the backend has a faster pass.
    virtual void postprocess(const WalrPassContext& ctx) { walrPostprocess(ctx, buffers); }
    /// The a-trous iterations from b.averages[0] and the solve into buffers.spatial.
    virtual void atrousAndSolve(const WalrPassContext& ctx) = 0;
};

} // namespace bmfr::reference
