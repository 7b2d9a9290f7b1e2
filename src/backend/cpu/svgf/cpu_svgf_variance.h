// SVGF's variance estimate on the CPU backend: svgfVariancePixel (filters/svgf/svgf_kernels.h)
// eight pixels at a time. Pixels with a long enough history take their moments' variance, bit
// for bit; the 7x7 bilateral estimate of short histories runs eight wide with one polynomial
// exponential per tap for the depth and luminance weights (rounded differently from the
// reference, within the conformance tolerance), and pixel by pixel within 3 of the sides.
#pragma once
#include "filters/svgf/svgf_kernels.h"

namespace bmfr::cpu {

/// The a-trous levels' first planes (CpuAtrous, cpu_svgf_atrous.h), rows `pitch` floats apart:
/// the guides (normal, 0 without a sample; depth; its gradient; 1 with a sample, else 0), and
/// the colour, variance and luminance.
struct SvgfFirstLevel {
    float *nx, *ny, *nz, *depth, *gradX, *gradY, *mask;
    float* colour[5];
    long pitch;
};

/// svgfVariancePixel over the rows [y0, y1), for settings that cpuNormalPowerSupports
/// (cpu_svgf_weights.h). With `level`, its planes get the result and the guides instead of
/// `filtered`, which then serves as scratch, and the depth gradient is made from f.depth
/// (svgfDepthGradient; svgfAccumulate without it), not read from f.depthGradient, which holds
/// it only where the reference's pixels needed it.
void svgfVarianceRows(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1, float* filtered,
                      float* variance, const SvgfFirstLevel* level = nullptr);

} // namespace bmfr::cpu
