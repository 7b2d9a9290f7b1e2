// History across shadow edges (BmfrSettings::visibilityTaps): with the key light's noise-free
// visibility, phase III and the same-surface TAA take no history tap from the other side of a
// shadow edge, so the edge the fit draws from the visibility stays sharp under jitter and
// motion. BMFR_HD: the reference and CUDA backends run these per pixel after the fit; the CPU
// backend's resolve pass does the same eight pixels at a time (filterTaps in cpu_resolve.cpp).
#pragma once
#include "filters/bmfr/emitter_exclusion.h"
#include "temporal/pixel_input.h"

namespace bmfr {

/// 1 where the key light reaches pixel i (visibility above 0), else 0 (NaN included).
BMFR_HD uint8_t litClass(const float* visibility, long i) {
    return visibility[i] > 0.0f ? 1 : 0;
}

/// The accepted taps of pixel i whose pixel had its lit class last frame: sameEmitterTaps on
/// lit classes. Sets lit[i] for this frame first; prevLit is null on a frame without history.
BMFR_HD uint8_t sameLitTaps(uint8_t accept, Vec2 previousPixel, const float* visibility,
                            const uint8_t* prevLit, uint8_t* lit, long i, int width) {
    lit[i] = litClass(visibility, i);
    return prevLit ? sameEmitterTaps(accept, previousPixel, prevLit, lit[i], width) : accept;
}

} // namespace bmfr
