// The interface a backend implements for SVGF, and the host buffers both host backends use.
#pragma once
#include "core/image.h"
#include "filters/filter_passes.h"
#include "filters/svgf/svgf_kernels.h"
#include <bmfr/filters/svgf_filter.h>
#include <memory>

namespace bmfr {

using SvgfPassContext = PassContext<SvgfSettings>;

/// SVGF's per-pixel buffers: the history (double-buffered) and this frame's, as images of F
/// (floats) and U (bytes): host Image<T> for the host backends, device images for CUDA.
template <class F, class U> struct SvgfImages {
    // History, [slot].
    F normal[2], position[2]; ///< sanitised features for the shared discard test
    F color[2];               ///< demodulated colour history (fed back from the step-1 level)
    F moments[2];             ///< 2 channels: luminance and luminance squared
    U historyLength[2];       ///< 0 = no sample yet (fewer than 1 spp)
    F output[2];              ///< final output (TAA history), 24 floats of padding
    // This frame.
    F integrated, depth, depthGradient;
    F variance;      ///< estimate before filtering (debug view)
    F filtered[2];   ///< a-trous ping-pong: RGB colour + variance
    F previousPixel; ///< 2 channels, shared with TAA
    U accept;
    F remodulated; ///< before TAA

    void allocate(int w, int h) {
        for (int k = 0; k < 2; ++k) {
            normal[k].resize(w, h, 3), position[k].resize(w, h, 3), color[k].resize(w, h, 3);
            moments[k].resize(w, h, 2), historyLength[k].resize(w, h, 1);
            output[k].resize(w, h, 3, 24), filtered[k].resize(w, h, 4);
        }
        integrated.resize(w, h, 3), depth.resize(w, h, 1);
        depthGradient.resize(w, h, 2), variance.resize(w, h, 1), previousPixel.resize(w, h, 2);
        accept.resize(w, h, 1), remodulated.resize(w, h, 3);
    }

    /// The kernels' view of this frame, reading the input from `in`.
    SvgfFrame frame(const SvgfPassContext& ctx, const InputPlanes& in) {
        const SvgfSettings& s = ctx.settings;
        const int cur = ctx.history.cur, prev = 1 - cur;
        SvgfFrame f;
        f.in = in;
        f.modes = {s.colorIsDemodulated, true, s.albedoEpsilon};
        f.previous = ctx.history.previous;
        f.viewProjection = ctx.frame.viewProjection;
        f.limits = {s.positionLimitSquared, s.normalLimitSquared};
        f.colorAlpha = s.colorAlpha, f.momentsAlpha = s.momentsAlpha;
        f.width = ctx.history.width, f.height = ctx.history.height;
        f.prevNormal = normal[prev].data(), f.prevPosition = position[prev].data();
        f.prevColor = color[prev].data(), f.prevMoments = moments[prev].data();
        f.prevLength = historyLength[prev].data();
        f.normal = normal[cur].data(), f.position = position[cur].data();
        f.color = color[cur].data(), f.moments = moments[cur].data();
        f.length = historyLength[cur].data();
        f.integrated = integrated.data();
        f.depth = depth.data(), f.depthGradient = depthGradient.data();
        f.previousPixel = previousPixel.data(), f.accept = accept.data();
        return f;
    }
};

/// SVGF's buffers in host memory, with the debug copies both host backends keep.
struct SvgfBuffers : SvgfImages<ImageF, ImageU8> {
    int outputLevel = 0;                        ///< which of filtered[] holds the last level
    ImageF historyLengthF, acceptF, finalLevel; ///< debug copies, sized on first use

    SvgfFrame frame(const SvgfPassContext& ctx) { return SvgfImages::frame(ctx, ctx.input); }
    ImageView result(int slot) const { return view(output[slot]); }
    DebugBuffers debug(int cur) const;
    void captureDebug(int cur);
};

/// The a-trous levels in the settings' order over the ping-pong pair filtered[0..1]: calls
/// level(from, to, step) for each, and keep(k) once filtered[k] holds the step-1 level (the
/// next frame's colour history). Returns which of filtered[] holds the last level.
template <class Level, class Keep>
int runAtrousLevels(const SvgfSettings& s, Level&& level, Keep&& keep) {
    int src = 0;
    for (int k = 0; k < s.iterations; ++k) {
        const int index = s.reverseLevels ? s.iterations - 1 - k : k;
        level(src, 1 - src, 1 << index);
        src = 1 - src;
        if (index == 0) keep(src);
    }
    return src;
}

/// One backend's SVGF passes: the shared ones and the variance view.
class SvgfPasses : public FilterPasses<SvgfSettings> {
  public:
    /// The variance estimate of the last frame before the a-trous filter (1 channel).
    virtual ImageView variance() const = 0;
};
template <> struct PassesOf<SvgfSettings> { using type = SvgfPasses; };

/// The part of a host backend's SVGF passes that only reads SvgfBuffers.
class HostSvgfPasses : public HostPasses<SvgfSettings, SvgfBuffers> {
  public:
    ImageView variance() const override { return view(buffers.variance); }
};

} // namespace bmfr
