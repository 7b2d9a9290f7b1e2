// SVGF's accumulation on the CPU backend: svgfAccumulatePixel (filters/svgf/svgf_kernels.h)
// eight pixels at a time, with the reference's decisions (discard masks, history lengths) bit
// for bit and its sums in the same order.
#pragma once
#include "filters/svgf/svgf_kernels.h"

namespace bmfr::cpu {

/// svgfAccumulatePixel over the rows [y0, y1); returns the non-finite values it counted.
int64_t svgfAccumulateRows(const SvgfFrame& f, long y0, long y1);

} // namespace bmfr::cpu
