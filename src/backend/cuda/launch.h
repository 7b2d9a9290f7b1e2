// Launch shapes of the CUDA executor's one-dimensional loops.
#pragma once
#include "core/host_device.h"

namespace bmfr::cuda {

/// Threads per block of the one-thread-per-pixel kernels.
inline constexpr int kPixelThreads = 256;
/// Blocks covering n pixels.
inline unsigned pixelBlocks(long n) {
    return unsigned((n + kPixelThreads - 1) / kPixelThreads);
}

#if defined(__CUDACC__)
/// This thread's pixel of a one-dimensional launch.
__device__ inline long pixelIndex() {
    return long(blockIdx.x) * blockDim.x + threadIdx.x;
}
#endif

} // namespace bmfr::cuda
