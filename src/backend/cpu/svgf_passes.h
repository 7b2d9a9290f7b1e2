// The CPU implementation of SVGF's passes.
#pragma once
#include "filters/svgf/svgf_state.h"
#include <cstdint>

namespace bmfr::cpu {

/// Reprojection (shared with BMFR), colour and moments accumulation, depth and its gradient.
/// Returns the count of non-finite input values replaced.
int64_t svgfAccumulate(const SvgfPassContext& ctx);
/// Variance from the moments; 7x7 bilateral spatial estimate for short histories. Fills
/// state.filtered[0] with colour + variance.
void svgfEstimateVariance(const SvgfPassContext& ctx);
/// One a-trous level with step `step` pixels from `in` to `out` (4 channels: RGB + variance).
/// Pixels without a sample (history length 0) are neither written from nor read into.
void svgfAtrous(ThreadPool& pool, const SvgfSettings& s, const ImageF& in, ImageF& out,
                const ImageF& normal, const ImageF& depth, const ImageF& depthGradient,
                const ImageU8& historyLength, int step);

} // namespace bmfr::cpu
