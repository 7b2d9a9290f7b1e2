// SVGF's variance estimate on the CPU backend: svgfVariancePixel (filters/svgf/svgf_kernels.h)
// eight pixels at a time, into the a-trous levels' first planes. Pixels with a long enough
// history take their moments' variance, bit for bit; the 7x7 bilateral estimate of short
// histories runs eight wide over the first level's planes with one polynomial exponential per
// tap for the depth and luminance weights (rounded differently from the reference, within the
// conformance tolerance), the taps past a side read as weight 0 from the planes' aprons.
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

/// The first level's planes but the variance over rows [y0, y1): the guides, with the depth
/// gradient made from f.depth (svgfDepthGradient; svgfAccumulate without it), and the colour
/// and its luminance.
void svgfFirstLevelRows(const SvgfFrame& f, const SvgfFirstLevel& level, long y0, long y1);

/// svgfVariancePixel's variance over rows [y0, y1) into the first level's variance plane and
/// `variance` (one float per pixel), for settings that cpuNormalPowerSupports
/// (cpu_svgf_weights.h), once svgfFirstLevelRows has made every row of the first level (the
/// 7x7 estimate reads its planes).
void svgfVarianceRows(const SvgfFrame& f, const SvgfSettings& s, const SvgfFirstLevel& level,
                      long y0, long y1, float* variance);

} // namespace bmfr::cpu
