// The interface a backend implements for Mara et al. 2017, and the host buffers both host
// backends use.
#pragma once
#include "core/image.h"
#include "filters/filter_passes.h"
#include "filters/mara2017/mara_stages.h"
#include "temporal/taa.h"
#include <bmfr/filters/mara2017_filter.h>
#include <memory>

namespace bmfr {

using MaraPassContext = PassContext<Mara2017Settings>;

/// The settings in the units the stages use at an image `width` pixels wide (radii in pixels);
/// no buffers.
MaraFrame maraFrameSettings(const Mara2017Settings& settings, int width);

/// Unit offsets of every one of the kMaraSpiralRotations rotations of a `taps`-tap spiral,
/// turned by the frame's rotation (radians): rotation-major, 2 floats per tap.
void maraSpiralTable(int taps, float frameRotation, std::vector<float>& out);

/// The `count` unit taps of a spiral table at `radius` pixels, as the sparse bilateral computes
/// them: whole-pixel offsets (2 per tap) and Gaussian weights of `sigma` pixels (1 per tap).
void maraTapTable(const float* spiral, int count, float radius, float sigma,
                  std::vector<int>& offsets, std::vector<float>& gauss);

/// Mara's per-pixel buffers in host memory: the history (double-buffered) and this frame's.
struct MaraBuffers {
    // History, [slot].
    ImageF matteHistory[2], glossyHistory[2]; ///< 3
    ImageF position[2], normal[2];            ///< sanitised features (3)
    ImageU8 count[2];
    ImageF output[2]; ///< final radiance (3); the previous one is TAA's history
    // This frame.
    ImageF matte, glossy, expected, previousPixel, temporal, confidence, glossyTemporal;
    ImageF rowMin, radius, median, matteOut, glossyRow, glossyOut, composed, ycocg;
    ImageU8 accept;
    std::vector<float> preSpiral, finalSpiral;
    std::vector<int> preOffsets;
    std::vector<float> preGauss;
    ImageF countF, acceptF; ///< debug copies, sized on first use

    void allocate(int w, int h);
    /// Room for the spiral tables of these settings, so that frame() allocates nothing.
    void reserveTables(const Mara2017Settings& s);
    /// The stages' view of this frame; builds this frame's spiral tables.
    MaraFrame frame(const MaraPassContext& ctx);
    TaaInputs taaInputs(const MaraPassContext& ctx) const;
    ImageView result(int slot) const { return view(output[slot]); }
    DebugBuffers debug(int cur) const;
    void captureDebug(int cur);
};

using MaraPasses = FilterPasses<Mara2017Settings>;

} // namespace bmfr
