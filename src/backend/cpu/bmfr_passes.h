// The CPU implementation of BMFR's passes: rows or blocks spread over all cores.
#pragma once
#include "filters/bmfr/state.h"
#include <cstdint>

namespace bmfr::cpu {

struct InputCounters {
    int64_t nonFinite = 0;
    int64_t discarded = 0;
};

/// Phase I: sanitise and store features, demodulate, reproject, test taps, accumulate colour.
InputCounters accumulateNoisy(const BmfrPassContext& ctx);
/// Phase II: per block gather, scale, regularise, Householder QR, back substitution, weighted sum.
void fitBlocks(const BmfrPassContext& ctx);
/// Phase III: second accumulation reusing phase I's taps, then re-modulation by albedo.
void accumulateFitted(const BmfrPassContext& ctx);
/// TAA with a 3x3 YCoCg neighbourhood clamp (Karis 2014, the authors' variant), bilinear history
/// at `previousPixel` (2 floats per pixel), weight `alpha` for the current frame. Shared by
/// every filter. ycocgScratch holds 3 floats per pixel. With enabled = false it copies `current`
/// to `out`.
void temporalAntiAliasing(ThreadPool& pool, const float* current, const float* history,
                          const float* previousPixel, float* ycocgScratch, float* out, int width,
                          int height, float alpha, bool enabled);

} // namespace bmfr::cpu
