// The interface a backend implements for WALR, and the host buffers both host backends use.
#pragma once
#include "core/image.h"
#include "filters/filter_passes.h"
#include "filters/walr/edge_tracing.h"
#include "filters/walr/walr_temporal_kernels.h"
#include <bmfr/filters/walr_filter.h>
#include <memory>
#include <vector>

namespace bmfr {

using WalrPassContext = PassContext<WalrSettings>;

/// Whether the settings step the edge trace (EdgeGuide::stepped).
inline bool walrSteppedTrace(const WalrSettings& s) {
    return s.edgeTracing && s.edgeStep > 0;
}

/// The memory behind SteppedTrace, in arrays A (std::vector on the host, a device array on
/// CUDA): each iteration's view reads the last one's flat runs.
template <template <class...> class A> struct SteppedTraceStore {
    A<float> min;
    A<int32_t> firstZero;
    A<uint8_t> flat[2];
    long pixels = 0;
    /// Sized for `pixels` pixels (0: none).
    void resize(long n) {
        pixels = n;
        min.resize(size_t(8 * n)), firstZero.resize(size_t(8 * n));
        for (A<uint8_t>& f : flat) f.resize(size_t(8 * n));
    }
    SteppedTrace at(int iteration) {
        return {min.data(), firstZero.data(), flat[(iteration + 1) % 2].data(),
                flat[iteration % 2].data(), pixels};
    }
};
using SteppedTraceBuffers = SteppedTraceStore<std::vector>;

/// WALR's per-pixel buffers, as images of F (floats) and U (bytes): host Image<T> for the host
/// backends, device images for CUDA. The history is double-buffered, by slot.
template <class F, class U> struct WalrImages {
    // History, [slot].
    F pre[2], post[2];        ///< preprocess and postprocess averages (3)
    F depth[2];               ///< view depth (1)
    F position[2], normal[2]; ///< sanitised features (3)
    U count[2];               ///< samples in the preprocess average
    // This frame.
    F signal, features, offset, expectedDepth, previousPixel, postHistory;
    U accept;
    /// A-trous ping-pong: kWalrAverages planes, or with `interleaved` 16 floats per pixel (a
    /// cache line: what the CPU backend reads per tap).
    F averages[2];
    bool interleaved = false;
    F weights[2]; ///< the sample-count weights W, when kept
    F spatial;    ///< the spatial filter's output (3)
    F output;     ///< final radiance (3)
    int lastAverages = 0;

    void allocate(int w, int h) {
        for (int k = 0; k < 2; ++k) {
            pre[k].resize(w, h, 3), post[k].resize(w, h, 3), depth[k].resize(w, h, 1);
            position[k].resize(w, h, 3), normal[k].resize(w, h, 3), count[k].resize(w, h, 1);
            averages[k].resize(w, h, interleaved ? 16 : kWalrAverages), weights[k].resize(w, h, 1);
        }
        signal.resize(w, h, 3), features.resize(w, h, 2), offset.resize(w, h, 2);
        expectedDepth.resize(w, h, 1), previousPixel.resize(w, h, 2), postHistory.resize(w, h, 3);
        accept.resize(w, h, 1), spatial.resize(w, h, 3), output.resize(w, h, 3);
    }
    AverageLayout layout() const {
        return interleaved ? AverageLayout{1, 16} : AverageLayout{signal.pixelCount(), 1};
    }

    /// The kernels' views of this frame, reading the input from ctx.input.
    WalrFrame frame(const WalrPassContext& ctx) {
        const WalrSettings& s = ctx.settings;
        const int cur = ctx.history.cur, prev = 1 - cur;
        WalrFrame f;
        f.in = ctx.input;
        if (s.signal == WalrSignal::Color) f.in.diffuseIndirect = nullptr;
        f.modes = {s.colorIsDemodulated, true, s.albedoEpsilon};
        f.previous = ctx.history.previous;
        f.viewProjection = ctx.frame.viewProjection;
        f.view = viewBasisOf(ctx.frame.viewProjection);
        f.limits = {s.positionLimitSquared, s.normalLimitSquared};
        f.preAlpha = s.preAlpha, f.depthTolerance = s.depthTolerance;
        f.depthTest = s.historyTest == WalrHistoryTest::Depth;
        f.dilation = s.motionDilation;
        f.width = ctx.history.width, f.height = ctx.history.height;
        f.prevPre = pre[prev].data(), f.prevPost = post[prev].data();
        f.prevDepth = depth[prev].data();
        f.prevPosition = position[prev].data(), f.prevNormal = normal[prev].data();
        f.prevCount = count[prev].data();
        f.pre = pre[cur].data(), f.depth = depth[cur].data(), f.position = position[cur].data();
        f.normal = normal[cur].data(), f.count = count[cur].data();
        f.signal = signal.data(), f.features = features.data(), f.offset = offset.data();
        f.expectedDepth = expectedDepth.data(), f.previousPixel = previousPixel.data();
        f.postHistory = postHistory.data(), f.accept = accept.data();
        return f;
    }
    EdgeGuide guide(const WalrPassContext& ctx) const {
        const WalrSettings& s = ctx.settings;
        const int cur = ctx.history.cur;
        EdgeGuide g;
        g.position = position[cur].data(), g.normal = normal[cur].data();
        g.depth = depth[cur].data();
        g.width = ctx.history.width, g.height = ctx.history.height;
        g.nearFraction = s.edgeNear, g.farFraction = s.edgeFar;
        g.tracing = s.edgeTracing, g.replacement = s.averageReplacement;
        g.stepFraction = s.edgeStep;
        return g;
    }
    WalrLevel level(const WalrPassContext& ctx, int t, bool keepWeights) {
        WalrLevel l;
        const int src = t % 2;
        l.in = averages[src].data(), l.out = averages[1 - src].data();
        l.weightIn = keepWeights && t > 0 ? weights[src].data() : nullptr;
        l.weightOut = keepWeights ? weights[1 - src].data() : nullptr;
        l.layout = layout();
        l.iteration = t;
        l.step = 1;
        for (int k = 0; k < t; ++k) l.step *= 3;
        l.frame = uint32_t(ctx.history.frameIndex);
        l.seed = ctx.settings.seed;
        // Level 0 comes from the preprocess and the last level goes to the solve, as floats.
        const int last = walrIterations(ctx.settings, ctx.history.width, ctx.history.height) - 1;
        l.halfIn = ctx.settings.halfAverages && t > 0;
        l.halfOut = ctx.settings.halfAverages && t < last;
        return l;
    }
    WalrPost postInputs(const WalrPassContext& ctx) {
        const WalrSettings& s = ctx.settings;
        const TemporalHistory& h = ctx.history;
        WalrPost p;
        p.in = ctx.input;
        p.spatial = spatial.data(), p.postHistory = postHistory.data(), p.signal = signal.data();
        p.count = count[h.cur].data(), p.post = post[h.cur].data(), p.output = output.data();
        p.width = h.width, p.height = h.height;
        p.alpha = s.taaBlendAlpha, p.gamma = s.varianceGamma, p.albedoEpsilon = s.albedoEpsilon;
        p.enabled = s.taa, p.diffuseIndirect = s.signal == WalrSignal::DiffuseIndirect;
        return p;
    }
};

/// WALR's buffers in host memory, with the debug views the host backends give.
struct WalrBuffers : WalrImages<ImageF, ImageU8> {
    ImageF countF, acceptF; ///< debug copies, sized on first use
    ImageView result(int) const { return view(output); }
    DebugBuffers debug(int cur) const {
        return {view(pre[cur]), view(spatial), view(countF), view(acceptF)};
    }
    void captureDebug(int cur) {
        widenToFloat(count[cur], countF);
        widenToFloat(accept, acceptF);
    }
};

using WalrPasses = FilterPasses<WalrSettings>;

} // namespace bmfr
