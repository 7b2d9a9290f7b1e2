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

/// The host memory behind SteppedTrace: each iteration's view reads the last one's flat runs.
struct SteppedTraceBuffers {
    std::vector<float> min;
    std::vector<int32_t> firstZero;
    std::vector<uint8_t> flat[2];
    long pixels = 0;
    /// Sized for `pixels` pixels (0: none).
    void resize(long n) {
        pixels = n;
        min.resize(size_t(8 * n)), firstZero.resize(size_t(8 * n));
        for (std::vector<uint8_t>& f : flat) f.resize(size_t(8 * n));
    }
    SteppedTrace at(int iteration) {
        return {min.data(), firstZero.data(), flat[(iteration + 1) % 2].data(),
                flat[iteration % 2].data(), pixels};
    }
};

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
