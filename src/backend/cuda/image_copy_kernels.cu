#include "backend/cuda/device_buffer.h"
#include "backend/cuda/image_copy.h"
#include "backend/cuda/launch.h"

namespace bmfr::cuda {

namespace {
__global__ void packKernel(const float* src, int srcChannels, long srcStride, int first,
                           int channels, int w, long n, float* dst) {
    const long i = pixelIndex();
    if (i >= n) return;
    const float* from = src + (i / w) * srcStride + (i % w) * srcChannels + first;
    for (int c = 0; c < channels; ++c) dst[i * channels + c] = from[c];
}
__global__ void unpackKernel(const float* src, int w, long n, float* dst, int dstChannels,
                             long dstStride) {
    const long i = pixelIndex();
    if (i >= n) return;
    float* to = dst + (i / w) * dstStride + (i % w) * dstChannels;
    for (int c = 0; c < 3; ++c) to[c] = src[3 * i + c];
}
} // namespace

void launchPackChannels(const float* src, int srcChannels, long srcStride, int first, int channels,
                        int w, int h, float* dst, cudaStream_t stream) {
    const long n = long(w) * h;
    packKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(src, srcChannels, srcStride, first,
                                                             channels, w, n, dst);
    check(cudaGetLastError(), "input packing kernel");
}

void launchUnpackRgb(const float* src, int w, int h, float* dst, int dstChannels, long dstStride,
                     cudaStream_t stream) {
    const long n = long(w) * h;
    unpackKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(src, w, n, dst, dstChannels,
                                                               dstStride);
    check(cudaGetLastError(), "output copy kernel");
}

} // namespace bmfr::cuda
