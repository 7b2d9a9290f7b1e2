// The interface a backend implements for WALR, and the host buffers both host backends use.
#pragma once
#include "core/image.h"
#include "filters/filter_passes.h"
#include "filters/walr/edge_tracing.h"
#include "filters/walr/walr_temporal_kernels.h"
#include <bmfr/filters/walr_filter.h>
#include <memory>

namespace bmfr {

using WalrPassContext = PassContext<WalrSettings>;

/// WALR's per-pixel buffers in host memory: the history (double-buffered) and this frame's.
struct WalrBuffers {
    // History, [slot].
    ImageF pre[2], post[2];        ///< preprocess and postprocess averages (3)
    ImageF depth[2];               ///< view depth (1)
    ImageF position[2], normal[2]; ///< sanitised features (3)
    ImageU8 count[2];              ///< samples in the preprocess average
    // This frame.
    ImageF signal, features, offset, expectedDepth, previousPixel, postHistory;
    ImageU8 accept;
    /// A-trous ping-pong: kWalrAverages planes, or with `interleaved` 16 floats per pixel (a
    /// cache line: what the CPU backend reads per tap).
    ImageF averages[2];
    bool interleaved = false;
    ImageF weights[2]; ///< the sample-count weights W, when kept
    ImageF spatial;    ///< the spatial filter's output (3)
    ImageF output;     ///< final radiance (3)
    int lastAverages = 0;
    ImageF countF, acceptF; ///< debug copies, sized on first use

    void allocate(int w, int h);
    AverageLayout layout() const {
        return interleaved ? AverageLayout{1, 16} : AverageLayout{signal.pixelCount(), 1};
    }
    /// The kernels' views of this frame.
    WalrFrame frame(const WalrPassContext& ctx);
    EdgeGuide guide(const WalrPassContext& ctx) const;
    WalrPost postInputs(const WalrPassContext& ctx);
    WalrLevel level(const WalrPassContext& ctx, int t, bool keepWeights);
    ImageView result(int) const { return view(output); }
    DebugBuffers debug(int cur) const;
    void captureDebug(int cur);
};

using WalrPasses = FilterPasses<WalrSettings>;

} // namespace bmfr
