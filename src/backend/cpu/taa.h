// Standalone TAA over whole images, for filters without a fused resolve pass (SVGF).
#pragma once
#include "core/parallel.h"

namespace bmfr::cpu {

/// TAA with a 3x3 YCoCg neighbourhood clamp (Karis 2014, the authors' variant) and bilinear
/// history at `previousPixel` (2 floats per pixel), weight `alpha` for the current frame.
/// `current`, `history` and `out` hold 3 floats per pixel; `history` must be readable 4 floats
/// past its end. `records` is scratch of 8 floats per pixel. With enabled = false, `out` gets
/// `current`.
void temporalAntiAliasing(ThreadPool& pool, const float* current, const float* history,
                          const float* previousPixel, float* records, float* out, int width,
                          int height, float alpha, bool enabled);

} // namespace bmfr::cpu
