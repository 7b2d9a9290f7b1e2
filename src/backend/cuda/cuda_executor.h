// The CUDA executor (core/executor.h): a stage's loop as one generic kernel over the stage's
// device lambda, on the frame's stream. For .cu files (nvcc with --extended-lambda).
#pragma once
#include "backend/cuda/device_buffer.h"
#include "backend/cuda/launch.h"
#include "core/executor.h"

namespace bmfr::cuda {

template <class F> __global__ void forEachIndexKernel(long n, F f) {
    const long i = pixelIndex();
    if (i < n) f(i);
}
template <class F> __global__ void forEachPixelKernel(int w, int h, F f) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x < w && y < h) f(x, y);
}

/// Launches on `stream`; checks each launch.
struct CudaExecutor {
    cudaStream_t stream;
    template <class F> void forEachIndex(long n, const F& f) const {
        if (n <= 0) return;
        forEachIndexKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(n, f);
        check(cudaGetLastError(), "kernel launch");
    }
    /// Tiles of 16 x 16 pixels: the neighbourhood taps of a tile share cache lines.
    template <class F> void forEachPixel(int w, int h, const F& f, long = 0) const {
        if (w <= 0 || h <= 0) return;
        const dim3 block(16, 16), grid(unsigned(w + 15) / 16, unsigned(h + 15) / 16);
        forEachPixelKernel<<<grid, block, 0, stream>>>(w, h, f);
        check(cudaGetLastError(), "kernel launch");
    }
};

} // namespace bmfr::cuda
