// The reference backend's SVGF stages up to TAA, each a plain loop over the filter's kernels
// (filters/svgf/svgf_kernels.h). The CPU backend runs these too and brings its own TAA.
#pragma once
#include "filters/svgf/svgf_passes.h"

namespace bmfr::reference {

/// Accumulation, depth gradient, variance, the a-trous levels (the step-1 level fed back as
/// the colour history) and re-modulation into b.remodulated. Returns the non-finite count.
PassCounters svgfStagesBeforeTaa(const SvgfPassContext& ctx, SvgfBuffers& b, StageTimes& times);

} // namespace bmfr::reference
