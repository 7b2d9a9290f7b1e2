// The CUDA backend's TAA pass, shared by its filters: each pixel's YCoCg once, then taaPixel
// (temporal/taa.h) per pixel. Without history (or with TAA off) the input is copied.
#pragma once
#include "temporal/taa.h"
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

/// `ycocg` holds 3 floats per pixel of scratch.
void launchTaa(const TaaInputs& in, float* ycocg, float* out, bool enabled, cudaStream_t stream);

} // namespace bmfr::cuda
