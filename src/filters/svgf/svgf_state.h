// What SVGF keeps between frames (double-buffered history) and its per-frame buffers.
#pragma once
#include "core/image.h"
#include "core/parallel.h"
#include <bmfr/frame.h>
#include <bmfr/svgf.h>

namespace bmfr {

struct SvgfState {
    int width = 0, height = 0, cur = 0;
    // History, [slot].
    ImageF normal[2], position[2]; ///< sanitised features for the shared discard test
    ImageF color[2];               ///< demodulated colour history (fed back from the step-1 level)
    ImageF moments[2];             ///< 2 channels: luminance and luminance squared
    ImageU8 historyLength[2];      ///< 0 = no sample yet (fewer than 1 spp)
    ImageF output[2];              ///< final output (TAA history), 4 floats of padding
    // This frame.
    ImageF integrated; ///< accumulated colour before filtering
    ImageF integratedMoments;
    ImageF depth;         ///< clip-space w (view depth) of the first hit
    ImageF depthGradient; ///< 2 channels: screen-space dz/dx, dz/dy
    ImageF variance;      ///< estimate before filtering (debug view)
    ImageF filtered[2];   ///< a-trous ping-pong: RGB colour + variance
    ImageF previousPixel; ///< 2 channels, shared with TAA
    ImageU8 accept;
    ImageF remodulated;
    ImageF taaRecords; ///< TAA scratch, cpu::taaScratchFloats(w, h) floats
    bool hasHistory = false;
    Mat4 previousViewProjection;
    float previousJitter[2] = {0, 0};

    void allocate(int w, int h);
};

struct SvgfPassContext {
    const SvgfSettings& settings;
    const FrameInput& frame;
    SvgfState& state;
    ThreadPool& pool;
};

} // namespace bmfr
