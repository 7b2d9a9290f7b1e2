// WALR's stages, each written once as loops of its per-pixel kernels on an executor
// (core/executor.h): the reference backend runs them on the host's threads, the CUDA backend as
// kernels, and the CPU backend replaces those it has faster. Images is WalrImages of either.
#pragma once
#include "core/executor.h"
#include "filters/walr/atrous_averages.h"
#include "filters/walr/refwlr.h"
#include "filters/walr/walr_passes.h"

namespace bmfr {

/// Passes 1a and 1b: inputs, reprojection, moving average and the level-0 averages (in
/// b.averages[0]); adds the non-finite inputs replaced to `nonFinite`.
template <class Exec, class Images>
void walrPreprocessStage(const Exec& e, const WalrPassContext& ctx, Images& b,
                         FrameCounter nonFinite) {
    const WalrFrame f = b.frame(ctx);
    e.forEachIndex(
        long(f.width) * f.height, BMFR_LAMBDA(long i) {
            int64_t bad = 0;
            walrInputPixel(f, i, bad);
            nonFinite.add(bad);
        });
    float* level0 = b.averages[0].data();
    const AverageLayout layout = b.layout();
    e.forEachPixel(
        f.width, f.height,
        BMFR_LAMBDA(int x, int y) { walrAccumulatePixel(f, x, y, level0, layout); });
}

/// REFWLR over the whole frame into b.spatial.
template <class Exec, class Images>
void walrRefwlrStage(const Exec& e, const WalrPassContext& ctx, Images& b) {
    const WalrSettings& s = ctx.settings;
    const EdgeGuide g = b.guide(ctx);
    int window = 1;
    const int iterations = walrIterations(s, g.width, g.height);
    for (int t = 0; t < iterations; ++t) window *= 3;
    const int radius = window / 2;
    const float* pre = b.pre[ctx.history.cur].data();
    const float* features = b.features.data();
    float* spatial = b.spatial.data();
    const float eps = s.pivotEpsilon;
    e.forEachPixel(
        g.width, g.height,
        BMFR_LAMBDA(int x, int y) {
            store3(spatial, long(y) * g.width + x,
                   refwlrPixel(g, pre, features, radius, eps, x, y));
        },
        1);
}

/// The a-trous iterations from b.averages[0]; `trace` (SteppedTraceStore) carries the stepped
/// trace's runs from one iteration to the next.
template <class Exec, class Images, class Trace>
void walrAtrousStage(const Exec& e, const WalrPassContext& ctx, Images& b, Trace& trace) {
    const WalrSettings& s = ctx.settings;
    const EdgeGuide g = b.guide(ctx);
    const int iterations = walrIterations(s, g.width, g.height);
    for (int t = 0; t < iterations; ++t) {
        WalrLevel l = b.level(ctx, t, s.sampleWeights);
        if (g.stepped()) l.trace = trace.at(t);
        e.forEachPixel(
            g.width, g.height, BMFR_LAMBDA(int x, int y) { walrAtrousPixel(g, l, x, y); }, 2);
    }
    b.lastAverages = iterations % 2;
}

/// The per-pixel solve of the last a-trous level (b.lastAverages) into b.spatial.
template <class Exec, class Images>
void walrSolveStage(const Exec& e, const WalrPassContext& ctx, Images& b) {
    const float* planes = b.averages[b.lastAverages].data();
    const AverageLayout layout = b.layout();
    const float* f = b.features.data();
    float* spatial = b.spatial.data();
    const float eps = ctx.settings.pivotEpsilon;
    e.forEachIndex(
        long(ctx.history.width) * ctx.history.height, BMFR_LAMBDA(long i) {
            store3(spatial, i, walrSolvePixel(planes, layout, i, {f[2 * i], f[2 * i + 1]}, eps));
        });
}

/// Pass 3: the variance-clipped post blend and the composition into b.output.
template <class Exec, class Images>
void walrPostprocessStage(const Exec& e, const WalrPassContext& ctx, Images& b) {
    const WalrPost p = b.postInputs(ctx);
    e.forEachPixel(
        p.width, p.height, BMFR_LAMBDA(int x, int y) { walrPostPixel(p, x, y); });
}

} // namespace bmfr
