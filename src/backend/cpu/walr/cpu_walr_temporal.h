// The CPU backend's WALR preprocess (passes 1a and 1b) and postprocess (pass 3), eight pixels
// at a time, with the reference's bits: the same operations in the same order, the same counts.
#pragma once
#include "filters/walr/walr_temporal_kernels.h"

namespace bmfr::cpu {

/// walrInputPixel over rows [y0, y1); returns the non-finite input values replaced.
int64_t walrInputRows(const WalrFrame& f, long y0, long y1);

/// walrAccumulatePixel over rows [y0, y1) into interleaved level-0 averages (16 floats per
/// pixel), after the input pass over the whole frame (the dilation reads neighbouring rows).
void walrAccumulateRows(const WalrFrame& f, long y0, long y1, float* averages);

/// walrPostPixel over rows [y0, y1).
void walrPostRows(const WalrPost& p, long y0, long y1);

} // namespace bmfr::cpu
