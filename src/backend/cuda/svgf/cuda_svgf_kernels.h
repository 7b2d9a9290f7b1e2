// The CUDA backend's SVGF kernels, as launches host C++ can call: one thread per pixel over
// the filter's BMFR_HD kernels (filters/svgf/svgf_kernels.h).
#pragma once
#include "filters/svgf/svgf_kernels.h"
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

/// Accumulation, then the depth gradient; counters[0] += non-finite input values.
void launchSvgfAccumulate(const SvgfFrame& f, unsigned long long* counters, cudaStream_t stream);
void launchSvgfVariance(const SvgfFrame& f, const SvgfSettings& s, float* filtered, float* variance,
                        cudaStream_t stream);
void launchSvgfAtrous(const AtrousLevel& level, const SvgfSettings& s, cudaStream_t stream);
/// colour history (3 floats) = the RGB of a level (4 floats per pixel).
void launchSvgfKeepLevel(const float* level, float* color, long pixels, cudaStream_t stream);
/// out = the last level's colour re-modulated with the input's albedo and emission.
void launchSvgfRemodulate(const float* level, const InputPlanes& in, float albedoEpsilon,
                          float* out, cudaStream_t stream);

} // namespace bmfr::cuda
