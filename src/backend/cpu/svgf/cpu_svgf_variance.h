// SVGF's variance estimate on the CPU backend: svgfVariancePixel (filters/svgf/svgf_kernels.h)
// eight pixels at a time. Pixels with a long enough history take their moments' variance, bit
// for bit; the 7x7 bilateral estimate of short histories runs eight wide with one polynomial
// exponential per tap for the depth and luminance weights (rounded differently from the
// reference, within the conformance tolerance), and pixel by pixel within 3 of the sides.
#pragma once
#include "filters/svgf/svgf_kernels.h"

namespace bmfr::cpu {

/// svgfVariancePixel over the rows [y0, y1), for settings that cpuNormalPowerSupports
/// (cpu_svgf_weights.h).
void svgfVarianceRows(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1, float* filtered,
                      float* variance);

} // namespace bmfr::cpu
