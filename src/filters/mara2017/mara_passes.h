// The interface a backend implements for Mara et al. 2017, and the host buffers both host
// backends use.
#pragma once
#include "core/image.h"
#include "core/view_basis.h"
#include "filters/filter_passes.h"
#include "filters/mara2017/mara_stages.h"
#include "temporal/taa.h"
#include <bmfr/filters/mara2017_filter.h>
#include <memory>
#include <vector>

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

/// Mara's per-pixel buffers, as images of F (floats) and U (bytes): host Image<T> for the host
/// backends, device images for CUDA. The history is double-buffered, by slot.
template <class F, class U> struct MaraImages {
    // History, [slot].
    F matteHistory[2], glossyHistory[2]; ///< 3
    F position[2], normal[2];            ///< sanitised features (3)
    U count[2];
    F output[2]; ///< final radiance (3); the previous one is TAA's history
    // This frame.
    F matte, glossy, expected, previousPixel, temporal, confidence, glossyTemporal;
    F rowMin, radius, median, matteOut, glossyRow, glossyOut, composed, ycocg;
    U accept;

    void allocate(int w, int h) {
        for (int k = 0; k < 2; ++k) {
            matteHistory[k].resize(w, h, 3), glossyHistory[k].resize(w, h, 3);
            position[k].resize(w, h, 3), normal[k].resize(w, h, 3), count[k].resize(w, h, 1);
            output[k].resize(w, h, 3);
        }
        for (F* img : {&matte, &glossy, &expected, &temporal, &glossyTemporal, &median, &matteOut,
                       &glossyRow, &glossyOut, &composed, &ycocg})
            img->resize(w, h, 3);
        previousPixel.resize(w, h, 2);
        confidence.resize(w, h, 1), rowMin.resize(w, h, 1), radius.resize(w, h, 1);
        accept.resize(w, h, 1);
    }

    /// The stages' view of this frame, without its tap tables (MaraTables::build sets them).
    MaraFrame frame(const MaraPassContext& ctx) {
        const Mara2017Settings& s = ctx.settings;
        const TemporalHistory& hist = ctx.history;
        const int cur = hist.cur, prev = 1 - cur, w = hist.width;
        MaraFrame f = maraFrameSettings(s, w);
        f.in = ctx.input;
        f.modes = {s.colorIsDemodulated, true, s.albedoEpsilon};
        f.previous = hist.previous;
        f.eye = viewBasisOf(ctx.frame.viewProjection).eye;
        f.width = w, f.height = hist.height;
        f.factored = f.in.matteIndirect != nullptr;
        f.glossy = f.factored && f.in.glossyIndirect != nullptr;
        f.frame = uint32_t(hist.frameIndex);
        f.prevMatte = matteHistory[prev].data(), f.prevGlossy = glossyHistory[prev].data();
        f.prevPosition = position[prev].data(), f.prevNormal = normal[prev].data();
        f.prevCount = count[prev].data();
        f.matteHistory = matteHistory[cur].data(), f.glossyHistory = glossyHistory[cur].data();
        f.position = position[cur].data(), f.normal = normal[cur].data();
        f.count = count[cur].data();
        f.matte = matte.data(), f.glossySignal = glossy.data(), f.expected = expected.data();
        f.previousPixel = previousPixel.data(), f.temporal = temporal.data();
        f.confidence = confidence.data(), f.glossyTemporal = glossyTemporal.data();
        f.rowMin = rowMin.data(), f.radius = radius.data(), f.median = median.data();
        f.matteOut = matteOut.data(), f.glossyRow = glossyRow.data();
        f.glossyOut = glossyOut.data();
        f.composed = composed.data(), f.accept = accept.data();
        return f;
    }
    TaaInputs taaInputs(const MaraPassContext& ctx) const {
        const TemporalHistory& h = ctx.history;
        return bmfr::taaInputs(composed.data(), output[1 - h.cur].data(), previousPixel.data(),
                               h.width, h.height, ctx.settings, accept.data());
    }
};

/// A frame's spiral and tap tables (stages 4 and 7), built on the host: the device copies them.
struct MaraTables {
    std::vector<float> preSpiral, finalSpiral;
    std::vector<int> preOffsets;
    std::vector<float> preGauss;
    /// Room for these settings' tables, so that build() allocates nothing.
    void reserve(const Mara2017Settings& s);
    /// This frame's tables (f's frame, radii and taps); points f at them.
    void build(const Mara2017Settings& s, MaraFrame& f);
};

/// Mara's buffers in host memory, with the tables and the debug views the host backends give.
struct MaraBuffers : MaraImages<ImageF, ImageU8> {
    MaraTables tables;
    ImageF countF, acceptF; ///< debug copies, sized on first use

    /// The stages' view of this frame; builds this frame's spiral tables.
    MaraFrame frame(const MaraPassContext& ctx) {
        MaraFrame f = MaraImages::frame(ctx);
        tables.build(ctx.settings, f);
        return f;
    }
    ImageView result(int slot) const { return view(output[slot]); }
    DebugBuffers debug(int) const {
        return {view(temporal), view(matteOut), view(countF), view(acceptF)};
    }
    void captureDebug(int cur) {
        widenToFloat(count[cur], countF);
        widenToFloat(accept, acceptF);
    }
};

using MaraPasses = FilterPasses<Mara2017Settings>;

} // namespace bmfr
