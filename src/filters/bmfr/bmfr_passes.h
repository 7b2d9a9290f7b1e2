// The interface a backend implements for BMFR (reference, cpu, cuda): the shared FilterPasses
// over BmfrSettings.
#pragma once
#include "filters/filter_passes.h"
#include <bmfr/filters/bmfr_filter.h>
#include <vector>

namespace bmfr {

using BmfrPassContext = PassContext<BmfrSettings>;
using BmfrPasses = FilterPasses<BmfrSettings>;

/// This frame's regularisation noise, M x blockPixels, as the host backends read it (the cuda
/// backend draws the same bits on its device).
void fillRegularisationNoise(const BmfrSettings& settings, long frameIndex,
                             std::vector<float>& noise);

} // namespace bmfr
