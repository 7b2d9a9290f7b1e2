// The interface a backend implements for SVGF, and the host buffers both host backends use.
#pragma once
#include "core/image.h"
#include "filters/filter_core.h"
#include "filters/svgf/svgf_kernels.h"
#include <bmfr/filters/svgf_filter.h>
#include <memory>

namespace bmfr {

using SvgfPassContext = PassContext<SvgfSettings>;

/// SVGF's per-pixel buffers in host memory: the history (double-buffered) and this frame's.
struct SvgfBuffers {
    // History, [slot].
    ImageF normal[2], position[2]; ///< sanitised features for the shared discard test
    ImageF color[2];               ///< demodulated colour history (fed back from the step-1 level)
    ImageF moments[2];             ///< 2 channels: luminance and luminance squared
    ImageU8 historyLength[2];      ///< 0 = no sample yet (fewer than 1 spp)
    ImageF output[2];              ///< final output (TAA history), 24 floats of padding
    // This frame.
    ImageF integrated, integratedMoments, depth, depthGradient;
    ImageF variance;      ///< estimate before filtering (debug view)
    ImageF filtered[2];   ///< a-trous ping-pong: RGB colour + variance
    ImageF previousPixel; ///< 2 channels, shared with TAA
    ImageU8 accept;
    ImageF remodulated;                         ///< before TAA
    int outputLevel = 0;                        ///< which of filtered[] holds the last level
    ImageF historyLengthF, acceptF, finalLevel; ///< debug copies, sized on first use

    void allocate(int w, int h);
    /// The kernels' view of this frame.
    SvgfFrame frame(const SvgfPassContext& ctx);
    DebugBuffers debug(int cur) const;
    void captureDebug(int cur);
};

/// One backend's SVGF passes.
class SvgfPasses {
  public:
    virtual ~SvgfPasses() = default;
    virtual void allocate(int w, int h) = 0;
    /// Runs every stage, writing the output to slot history.cur; returns the count of non-finite
    /// input values replaced.
    virtual int64_t run(const SvgfPassContext& ctx, StageTimes& times) = 0;
    virtual ImageView output(int slot) const = 0;
    virtual ImageView variance() const = 0;
    virtual void captureDebug(int cur) = 0;
    virtual DebugBuffers debug(int cur) const = 0;
};

/// The part of a host backend's SVGF passes that only reads SvgfBuffers.
class HostSvgfPasses : public SvgfPasses {
  public:
    ImageView output(int slot) const override { return view(buffers.output[slot]); }
    ImageView variance() const override { return view(buffers.variance); }
    void captureDebug(int cur) override { buffers.captureDebug(cur); }
    DebugBuffers debug(int cur) const override { return buffers.debug(cur); }

  protected:
    SvgfBuffers buffers;
};

} // namespace bmfr
