// Everything BMFR keeps between frames (double-buffered history) and its per-frame buffers.
#pragma once
#include "core/image.h"
#include "core/parallel.h"
#include <bmfr/frame.h>
#include <bmfr/settings.h>
#include <memory>
#include <vector>

namespace bmfr {

/// Per-thread scratch of the block fitter: one block's columns, contiguous.
struct FitScratch {
    std::vector<float> clean;    ///< M scaled feature columns, noise-free (used for the sum)
    std::vector<float> work;     ///< M noised columns + 3 colour columns, overwritten by QR
    std::vector<float> sum;      ///< 3 x W weighted-sum accumulators
    std::vector<float> soa;      ///< (6 + 16) x W gathered normal, position and extras
    std::vector<int> imageIndex; ///< image pixel of each block pixel, -1 when not owned
};

struct BmfrState {
    int width = 0, height = 0;
    int cur = 0; ///< history slot written this frame; 1 - cur holds the previous frame

    // History, [slot].
    ImageF normal[2], position[2]; ///< sanitised features (discard tests)
    ImageF accumulatedNoisy[2];    ///< phase I output, demodulated
    ImageU8 historyLength[2];      ///< phase I sample count, 1..255
    ImageF accumulatedFitted[2];   ///< phase III accumulation, demodulated
    ImageF output[2];              ///< final (TAA) output, linear

    // This frame only.
    ImageF previousPixel;  ///< 2 channels: continuous pixel in the previous frame
    ImageU8 acceptMask;    ///< accepted bilinear taps, bit i = tap i
    ImageF fitted;         ///< phase II output, demodulated
    ImageF remodulated;    ///< phase III output before TAA
    ImageF ycocg;          ///< TAA scratch
    ImageF historyLengthF; ///< debug copy of the history length as float
    ImageF acceptMaskF;    ///< debug copy of the accept mask as float

    std::vector<float> noise;        ///< M x blockPixels regularisation noise of this frame
    std::vector<FitScratch> scratch; ///< one per worker thread

    bool hasHistory = false;
    Mat4 previousViewProjection;
    float previousJitter[2] = {0, 0};
    long frameIndex = 0; ///< frames since construction: block offset and noise index

    void allocate(int w, int h, const Settings& s, int threads);
};

/// Inputs of one frame's passes.
struct BmfrPassContext {
    const Settings& settings;
    const FrameInput& frame;
    BmfrState& state;
    ThreadPool& pool;
};

} // namespace bmfr
