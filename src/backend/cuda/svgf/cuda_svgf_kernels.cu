// SVGF on the GPU, one thread per pixel. Built with --fmad=false: the discard decisions and
// history lengths must be the reference backend's, bit for bit.
#include "backend/cuda/device_buffer.h"
#include "backend/cuda/launch.h"
#include "backend/cuda/svgf/cuda_svgf_kernels.h"
#include "temporal/modulation.h"

namespace bmfr::cuda {

namespace {
__global__ void accumulateKernel(SvgfFrame f, unsigned long long* counters) {
    const long i = pixelIndex();
    if (i >= long(f.width) * f.height) return;
    int64_t bad = 0;
    svgfAccumulatePixel(f, i, bad);
    countIf(&counters[0], bad);
    // FrameStats::discardedPixels, as the host backends' countDiscarded.
    countIf(&counters[1], f.previous.valid && f.accept[i] == 0);
}
__global__ void depthGradientKernel(SvgfFrame f) {
    const long i = pixelIndex();
    if (i < long(f.width) * f.height) svgfDepthGradientPixel(f, int(i % f.width), int(i / f.width));
}
__global__ void varianceKernel(SvgfFrame f, SvgfSettings s, float* filtered, float* variance) {
    const long i = pixelIndex();
    if (i < long(f.width) * f.height)
        svgfVariancePixel(f, s, int(i % f.width), int(i / f.width), filtered, variance);
}
__global__ void atrousKernel(AtrousLevel a, SvgfSettings s) {
    const long i = pixelIndex();
    if (i < long(a.width) * a.height) svgfAtrousPixel(a, s, int(i % a.width), int(i / a.width));
}
__global__ void keepLevelKernel(const float* level, float* color, long n) {
    const long i = pixelIndex();
    if (i < n) store3(color, i, load3Stride4(level, i));
}
__global__ void remodulateKernel(const float* level, InputPlanes in, float eps, float* out) {
    const long i = pixelIndex();
    if (i < long(in.width) * in.height)
        store3(out, i, remodulatePixel(load3Stride4(level, i), in, i, true, eps));
}
} // namespace

void launchSvgfAccumulate(const SvgfFrame& f, unsigned long long* counters, cudaStream_t stream) {
    const long n = long(f.width) * f.height;
    accumulateKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(f, counters);
    check(cudaGetLastError(), "SVGF accumulation kernel");
    depthGradientKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(f);
    check(cudaGetLastError(), "SVGF depth gradient kernel");
}

void launchSvgfVariance(const SvgfFrame& f, const SvgfSettings& s, float* filtered, float* variance,
                        cudaStream_t stream) {
    const long n = long(f.width) * f.height;
    varianceKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(f, s, filtered, variance);
    check(cudaGetLastError(), "SVGF variance kernel");
}

void launchSvgfAtrous(const AtrousLevel& level, const SvgfSettings& s, cudaStream_t stream) {
    const long n = long(level.width) * level.height;
    atrousKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(level, s);
    check(cudaGetLastError(), "SVGF a-trous kernel");
}

void launchSvgfKeepLevel(const float* level, float* color, long pixels, cudaStream_t stream) {
    keepLevelKernel<<<pixelBlocks(pixels), kPixelThreads, 0, stream>>>(level, color, pixels);
    check(cudaGetLastError(), "SVGF colour history kernel");
}

void launchSvgfRemodulate(const float* level, const InputPlanes& in, float albedoEpsilon,
                          float* out, cudaStream_t stream) {
    const long n = long(in.width) * in.height;
    remodulateKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(level, in, albedoEpsilon, out);
    check(cudaGetLastError(), "SVGF re-modulation kernel");
}

} // namespace bmfr::cuda
