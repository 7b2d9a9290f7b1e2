// The fitter's per-block masks on the CPU: the firefly clamp, then the emitter mask.
#pragma once
#include "backend/cpu/bmfr/cpu_bmfr_buffers.h"
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

/// The firefly clamp (filters/bmfr/firefly_clamp.h) of block (bx, by)'s colour columns, the last
/// 3 of the M + 3 in `columns`, then its emitter mask (excludeEmitterRows), left in sc.mask.
/// Returns how many pixels the mask leaves out of the fit (their rows are zero).
int clampAndMaskBlock(const BlockMaskArgs& a, int bx, int by, float* columns, Scratch& sc);

} // namespace bmfr::cpu
