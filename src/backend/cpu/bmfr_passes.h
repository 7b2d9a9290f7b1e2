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
/// Phase III: TAA with a YCoCg neighbourhood clamp.
void temporalAntiAliasing(const BmfrPassContext& ctx);

} // namespace bmfr::cpu
