// Built with --fmad=false: TAA must round as the reference backend does.
#include "backend/cuda/cuda_taa.h"
#include "backend/cuda/device_buffer.h"
#include "backend/cuda/launch.h"

namespace bmfr::cuda {

namespace {
__global__ void ycocgKernel(TaaInputs a, float* out, long n) {
    const long i = pixelIndex();
    if (i < n) store3(out, i, rgbToYCoCg(taaSpace(a, load3(a.current, i))));
}
__global__ void taaKernel(TaaInputs a, float* out) {
    const long i = pixelIndex();
    if (i >= long(a.width) * a.height) return;
    store3(out, i, taaPixel(a, int(i % a.width), int(i / a.width)));
}
} // namespace

void launchTaa(const TaaInputs& in, float* ycocg, float* out, bool enabled, cudaStream_t stream) {
    const long n = long(in.width) * in.height;
    if (!enabled) {
        check(cudaMemcpyAsync(out, in.current, size_t(n) * 3 * sizeof(float),
                              cudaMemcpyDeviceToDevice, stream),
              "TAA copy");
        return;
    }
    ycocgKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(in, ycocg, n);
    check(cudaGetLastError(), "TAA YCoCg kernel");
    TaaInputs a = in;
    a.ycocg = ycocg;
    taaKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(a, out);
    check(cudaGetLastError(), "TAA kernel");
}

} // namespace bmfr::cuda
