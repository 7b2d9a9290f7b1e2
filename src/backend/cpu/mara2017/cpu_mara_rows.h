// The CPU backend's eight-wide Mara 2017 stages over rows: the sparse bilaterals (each pixel
// its own taps, gathered), the firefly median and the glossy passes (eight neighbouring pixels
// per tap). They give the reference stages' bits: the same operations in the same order, no
// fused multiply-adds.
#pragma once
#include "filters/mara2017/mara_stages.h"

namespace bmfr::cpu {

/// Stage 6 on rows [y0, y1) into f.median.
void maraMedianRows(const MaraFrame& f, long y0, long y1);

/// Stage 4 (`final` false: f.temporal into f.matteHistory) or stage 7 (`final` true: src into
/// f.matteOut) on rows [y0, y1), eight pixels at a time, each with its own taps.
void maraSparseRows(const MaraFrame& f, const float* src, bool final, long y0, long y1);

/// One glossy pass (stage 9 with (dx, dy) = (1, 0), stage 10 with (0, 1)) of src into dst on
/// rows [y0, y1). Eight pixels sharing one roughness run together; the others one by one.
void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, int dx,
                    int dy);

} // namespace bmfr::cpu
