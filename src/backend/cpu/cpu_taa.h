// Standalone TAA over whole images, for filters without a fused resolve pass (SVGF).
#pragma once
#include "core/parallel.h"
#include "temporal/pixel_input.h"
#include "temporal/taa.h"
#include <cstddef>
#include <cstdint>

namespace bmfr::cpu {

/// The frame TAA resolves: packed RGB (3 floats per pixel), or, with `planes` set, R, G and B
/// planes (rows `pitch` floats apart) re-modulated by `in`'s albedo on the way (SVGF's last
/// level), so that no re-modulated copy is written and read back.
struct TaaCurrent {
    const float* rgb = nullptr;
    const float* planes[3] = {};
    long pitch = 0;
    const InputPlanes* in = nullptr;
    float albedoEpsilon = 0.0f; ///< remodulate's guard (temporal/modulation.h)
};

/// Floats of scratch temporalAntiAliasing needs for images `width` pixels wide on a pool of
/// `threads` workers.
size_t taaScratchFloats(int width, int threads);

/// TAA with a 3x3 YCoCg neighbourhood clamp (Karis 2014, the authors' variant) and bilinear
/// history at `previousPixel` (2 floats per pixel), `blend` weighing the current frame.
/// `history` and `out` hold 3 floats per pixel. `scratch` holds taaScratchFloats(width, the pool's
/// threads) floats. With enabled = false, `out` gets `current`. `accept` (accept masks, or null)
/// restricts the history to the accepted taps (TaaInputs::accept); `space` is where it blends
/// (TaaInputs::space).
void temporalAntiAliasing(ThreadPool& pool, const TaaCurrent& current, const float* history,
                          const float* previousPixel, float* scratch, float* out, int width,
                          int height, TaaBlend blend, bool enabled, const uint8_t* accept,
                          TaaSpace space);

} // namespace bmfr::cpu
