// Phase I and phase III of BMFR on the GPU, one thread per pixel. Built with --fmad=false: the
// discard decisions and history lengths must be the reference backend's, bit for bit.
#include "backend/cuda/bmfr/cuda_bmfr_kernels.h"
#include "backend/cuda/device_buffer.h"
#include "backend/cuda/launch.h"
#include "filters/bmfr/regularisation_noise.h"
#include "filters/bmfr/second_grid.h"
#include "filters/bmfr/visibility_taps.h"

namespace bmfr::cuda {

namespace {
template <class H>
__global__ void accumulateNoisyKernel(NoisyAccumulationOf<H> a, unsigned long long* counters) {
    const long i = pixelIndex();
    if (i >= long(a.width) * a.height) return;
    int64_t bad = 0;
    const bool lost = accumulateNoisyPixel(a, i, bad);
    countIf(&counters[0], bad);
    countIf(&counters[1], lost ? 1 : 0);
}
template <class H>
__global__ void accumulateFittedKernel(FittedAccumulationOf<H> a, float* out, long n) {
    const long i = pixelIndex();
    if (i < n) store3(out, i, accumulateFittedPixel(a, i));
}
__global__ void sameEmitterTapsKernel(uint8_t* accept, const float* pp, const uint8_t* prevEmitter,
                                      const uint8_t* emitter, int width, long n) {
    const long i = pixelIndex();
    if (i < n)
        accept[i] =
            sameEmitterTaps(accept[i], {pp[2 * i], pp[2 * i + 1]}, prevEmitter, emitter[i], width);
}
__global__ void sameLitTapsKernel(uint8_t* accept, const float* pp, const float* visibility,
                                  const uint8_t* prevLit, uint8_t* lit, int width, long n) {
    const long i = pixelIndex();
    if (i < n)
        accept[i] =
            sameLitTaps(accept[i], {pp[2 * i], pp[2 * i + 1]}, visibility, prevLit, lit, i, width);
}
__global__ void widenKernel(const Half* from, float* to, long n) {
    const long i = pixelIndex();
    if (i < n) to[i] = float(from[i]);
}
__global__ void blendSecondFitKernel(float* fitted, const float* second, const uint8_t* length,
                                     long n) {
    const long i = pixelIndex();
    if (i < n && historyPoor(length[i]))
        for (int c = 0; c < 3; ++c)
            fitted[3 * i + c] = blendSecondFit(fitted[3 * i + c], second[3 * i + c]);
}
__global__ void historyChangeKernel(float* tiles, const float* change, int width, int height,
                                    float threshold, float gain) {
    const long k = pixelIndex(), tilesX = changeTilesX(width);
    if (k < tilesX * changeTilesY(height))
        storeTileChange(tiles, k,
                        tileHistoryChange(change, change + 1, 2, width, height, int(k % tilesX),
                                          int(k / tilesX), threshold, gain));
}
__global__ void noiseKernel(float* noise, const Feature* features, int M, int W, uint32_t seed,
                            uint32_t frame, float amplitude) {
    const long i = pixelIndex();
    if (i >= long(M) * W) return;
    const int f = int(i / W), k = int(i % W);
    noise[i] =
        regularisationNoise(seed, frame, f, k, amplitude, features[f].source == FeatureSource::One);
}
} // namespace

template <class H>
void launchAccumulateNoisy(const NoisyAccumulationOf<H>& a, unsigned long long* counters,
                           cudaStream_t stream) {
    const long n = long(a.width) * a.height;
    accumulateNoisyKernel<H><<<pixelBlocks(n), kPixelThreads, 0, stream>>>(a, counters);
    check(cudaGetLastError(), "phase I kernel");
}

template <class H>
void launchAccumulateFitted(const FittedAccumulationOf<H>& a, float* out, cudaStream_t stream) {
    const long n = long(a.width) * a.in.height;
    accumulateFittedKernel<H><<<pixelBlocks(n), kPixelThreads, 0, stream>>>(a, out, n);
    check(cudaGetLastError(), "phase III kernel");
}

template void launchAccumulateNoisy(const NoisyAccumulationOf<float>&, unsigned long long*,
                                    cudaStream_t);
template void launchAccumulateNoisy(const NoisyAccumulationOf<Half>&, unsigned long long*,
                                    cudaStream_t);
template void launchAccumulateFitted(const FittedAccumulationOf<float>&, float*, cudaStream_t);
template void launchAccumulateFitted(const FittedAccumulationOf<Half>&, float*, cudaStream_t);

void launchToFloat(const float* from, float* to, long n, cudaStream_t stream) {
    check(cudaMemcpyAsync(to, from, size_t(n) * sizeof(float), cudaMemcpyDeviceToDevice, stream),
          "float copy");
}
void launchToFloat(const Half* from, float* to, long n, cudaStream_t stream) {
    widenKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(from, to, n);
    check(cudaGetLastError(), "half widening kernel");
}

void launchSameEmitterTaps(uint8_t* accept, const float* previousPixel, const uint8_t* prevEmitter,
                           const uint8_t* emitter, int width, int height, cudaStream_t stream) {
    const long n = long(width) * height;
    sameEmitterTapsKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(
        accept, previousPixel, prevEmitter, emitter, width, n);
    check(cudaGetLastError(), "emitter taps kernel");
}

void launchSameLitTaps(uint8_t* accept, const float* previousPixel, const float* visibility,
                       const uint8_t* prevLit, uint8_t* lit, int width, int height,
                       cudaStream_t stream) {
    const long n = long(width) * height;
    sameLitTapsKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(
        accept, previousPixel, visibility, prevLit, lit, width, n);
    check(cudaGetLastError(), "shadow edge taps kernel");
}

void launchBlendSecondFit(float* fitted, const float* second, const uint8_t* length, long pixels,
                          cudaStream_t stream) {
    blendSecondFitKernel<<<pixelBlocks(pixels), kPixelThreads, 0, stream>>>(fitted, second, length,
                                                                            pixels);
    check(cudaGetLastError(), "second grid blend kernel");
}

void launchHistoryChange(float* tiles, const float* change, int width, int height, float threshold,
                         float gain, cudaStream_t stream) {
    const long n = long(changeTilesX(width)) * changeTilesY(height);
    historyChangeKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(tiles, change, width, height,
                                                                      threshold, gain);
    check(cudaGetLastError(), "history change kernel");
}

void launchNoise(float* noise, const Feature* features, int featureCount, int blockPixels,
                 uint32_t seed, uint32_t frame, float amplitude, cudaStream_t stream) {
    const long n = long(featureCount) * blockPixels;
    noiseKernel<<<pixelBlocks(n), kPixelThreads, 0, stream>>>(noise, features, featureCount,
                                                              blockPixels, seed, frame, amplitude);
    check(cudaGetLastError(), "noise kernel");
}

} // namespace bmfr::cuda
