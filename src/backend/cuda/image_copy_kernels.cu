#include "backend/cuda/cuda_executor.h"
#include "backend/cuda/image_copy.h"

namespace bmfr::cuda {

void launchPackChannels(const float* src, int srcChannels, long srcStride, int first, int channels,
                        int w, int h, float* dst, cudaStream_t stream) {
    CudaExecutor{stream}.forEachIndex(
        long(w) * h, BMFR_LAMBDA(long i) {
            const float* from = src + (i / w) * srcStride + (i % w) * srcChannels + first;
            for (int c = 0; c < channels; ++c) dst[i * channels + c] = from[c];
        });
}

void launchUnpackRgb(const float* src, int w, int h, float* dst, int dstChannels, long dstStride,
                     cudaStream_t stream) {
    CudaExecutor{stream}.forEachIndex(
        long(w) * h, BMFR_LAMBDA(long i) {
            float* to = dst + (i / w) * dstStride + (i % w) * dstChannels;
            for (int c = 0; c < 3; ++c) to[c] = src[3 * i + c];
        });
}

} // namespace bmfr::cuda
