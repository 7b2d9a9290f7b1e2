// The reference CPU implementation of BMFR's passes: one straightforward pass per stage, kept
// beside the fast passes as their specification (tests compare the two).
#pragma once
#include "core/image.h"
#include "filters/bmfr/state.h"

namespace bmfr::reference {

/// Per-thread scratch of the block fitter: one block's columns, contiguous.
struct FitScratch {
    std::vector<float> clean;    ///< M scaled feature columns, noise-free (used for the sum)
    std::vector<float> work;     ///< M noised columns + 3 colour columns, overwritten by QR
    std::vector<float> sum;      ///< 3 x W weighted-sum accumulators
    std::vector<float> soa;      ///< (6 + 16) x W gathered normal, position and extras
    std::vector<int> imageIndex; ///< image pixel of each block pixel, -1 when not owned
};

/// The reference passes' buffers, plain interleaved images.
struct Buffers {
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

    std::vector<FitScratch> scratch; ///< one per worker thread
};

/// Phase I: sanitise and store features, demodulate, reproject, test taps, accumulate colour.
InputCounters accumulateNoisy(const BmfrPassContext& ctx, Buffers& b);
/// Phase II: per block gather, scale, regularise, Householder QR, back substitution, weighted sum.
void fitBlocks(const BmfrPassContext& ctx, Buffers& b);
/// Phase III: second accumulation reusing phase I's taps, then re-modulation by albedo.
void accumulateFitted(const BmfrPassContext& ctx, Buffers& b);
/// TAA with a 3x3 YCoCg neighbourhood clamp (Karis 2014, the authors' variant), bilinear history
/// at `previousPixel` (2 floats per pixel), weight `alpha` for the current frame. ycocgScratch
/// holds 3 floats per pixel. With enabled = false it copies `current` to `out`.
void temporalAntiAliasing(ThreadPool& pool, const float* current, const float* history,
                          const float* previousPixel, float* ycocgScratch, float* out, int width,
                          int height, float alpha, bool enabled);

} // namespace bmfr::reference
