// The reference backend's TAA pass, for every filter: taaPixel (temporal/taa.h) over the image.
#pragma once
#include "core/parallel.h"
#include "temporal/taa.h"

namespace bmfr::reference {

/// TAA of `current` into `out` (3 floats per pixel each) with the history at `previousPixel`;
/// `ycocgScratch` holds 3 floats per pixel. With enabled = false, `out` gets `current`.
void taaPass(ThreadPool& pool, const TaaInputs& in, float* ycocgScratch, float* out, bool enabled);

} // namespace bmfr::reference
