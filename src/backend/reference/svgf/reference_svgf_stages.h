// The reference backend's SVGF stages up to TAA, each a plain loop over the filter's kernels
// (filters/svgf/svgf_kernels.h). The CPU backend runs these too, with its own accumulation
// rows, a-trous levels and TAA, eight wide.
#pragma once
#include "filters/svgf/svgf_passes.h"

namespace bmfr::reference {

/// svgfAccumulatePixel over the rows [y0, y1); returns the non-finite values it counted.
int64_t svgfAccumulatePixels(const SvgfFrame& f, long y0, long y1);
using SvgfAccumulateRows = int64_t (*)(const SvgfFrame& f, long y0, long y1);

/// svgfVariancePixel over the rows [y0, y1), into filtered (4 floats per pixel) and variance.
void svgfVariancePixels(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1,
                        float* filtered, float* variance);
using SvgfVarianceRows = void (*)(const SvgfFrame& f, const SvgfSettings& s, long y0, long y1,
                                  float* filtered, float* variance);

/// Accumulation (`rows` over every row) and, with `depthGradient`, the depth gradient
/// ("accumulate"). Returns the non-finite and discarded counts.
PassCounters svgfAccumulate(const SvgfPassContext& ctx, SvgfBuffers& b, StageTimes& times,
                            SvgfAccumulateRows rows = svgfAccumulatePixels,
                            bool depthGradient = true);
/// svgfAccumulate, then the variance estimate (`varianceRows`, "variance") into b.filtered[0].
PassCounters svgfAccumulateAndVariance(const SvgfPassContext& ctx, SvgfBuffers& b,
                                       StageTimes& times,
                                       SvgfAccumulateRows rows = svgfAccumulatePixels,
                                       SvgfVarianceRows varianceRows = svgfVariancePixels);
/// The a-trous levels' guides (normal, depth, its gradient, history length) for this frame.
AtrousLevel atrousGuides(const SvgfPassContext& ctx, SvgfBuffers& b);
/// The a-trous levels from b.filtered[0]: the step-1 level fed back as the colour history, the
/// last one's index in b.outputLevel.
void svgfAtrousLevels(const SvgfPassContext& ctx, SvgfBuffers& b);
/// The last level re-modulated into b.remodulated.
void svgfRemodulate(const SvgfPassContext& ctx, SvgfBuffers& b);
/// All of the above, the a-trous levels and re-modulation timed as "atrous".
PassCounters svgfStagesBeforeTaa(const SvgfPassContext& ctx, SvgfBuffers& b, StageTimes& times);

} // namespace bmfr::reference
