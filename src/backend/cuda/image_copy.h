// Copies between the packed planes the kernels read and write and the caller's interleaved
// device images (RGBA, padded rows).
#pragma once
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

/// dst (w x h x channels, packed) = channels [first, first + channels) of the interleaved
/// device image src (srcChannels per pixel, srcStride floats per row).
void launchPackChannels(const float* src, int srcChannels, long srcStride, int first, int channels,
                        int w, int h, float* dst, cudaStream_t stream);
/// The first three channels of dst (dstChannels per pixel, dstStride floats per row) = the
/// packed RGB image src; a fourth channel is left as it was.
void launchUnpackRgb(const float* src, int w, int h, float* dst, int dstChannels, long dstStride,
                     cudaStream_t stream);

} // namespace bmfr::cuda
