// The fitter's per-block masks on the CPU: the firefly clamp, then the emitter mask.
#pragma once
#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
#include "backend/cpu/simd.h"
#include "filters/bmfr/fitting_kernel.h"

namespace bmfr::cpu {

/// What the masks of one frame's blocks read.
struct BlockMaskArgs {
    BlockGrid grid;
    const InputPlanes& in;
    EmitterExclusion emitters;
    bool clampFireflies = false; ///< BmfrSettings::clampFireflies
    const PlaneSet& noisy; ///< phase I's output; channel 3, the history length, fades the clamp
    int featureCount = 0;  ///< M
    long stride = 0;       ///< floats between the QR's columns
};

/// maskBucket (filters/bmfr/emitter_exclusion.h) of eight luminances, from the same bits.
BMFR_SIMD_INLINE simd::i8 maskBucket8(simd::f8 lum) {
    using simd::i8;
    i8 bits;
    std::memcpy(&bits, &lum, sizeof bits);
    const i8 e = (bits >> 23) - 126;                // the sign bit is clear wherever lum > 0
    const i8 upper = (bits & 0x7FFFFF) >= 0x3504F3; // -1 where the mantissa is in the upper half
    i8 b = 2 * e + 47 - upper;
    b = b < 1 ? i8{} + 1 : b;
    b = b > kMaskBuckets - 1 ? i8{} + (kMaskBuckets - 1) : b;
    return lum > 0.0f ? b : i8{};
}

/// The firefly clamp (filters/bmfr/firefly_clamp.h) of block (bx, by)'s colour columns, the last
/// 3 of the M + 3 in `columns`, then its emitter mask (excludeEmitterRows), left in sc.mask.
/// Returns how many pixels the mask leaves out of the fit (their rows are zero).
int clampAndMaskBlock(const BlockMaskArgs& a, int bx, int by, float* columns, Scratch& sc);

} // namespace bmfr::cpu
