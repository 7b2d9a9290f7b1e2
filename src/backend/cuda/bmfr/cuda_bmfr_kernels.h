// The CUDA backend's BMFR kernels, as launches host C++ can call: phase I and phase III one
// thread per pixel over the shared BMFR_HD kernels, the regularisation noise, and the
// block-cooperative fit (cooperative_fit.h), one CUDA block per regression block. Those that
// touch the history take it as float or, under halfHistory, as Half (H).
#pragma once
#include "filters/bmfr/accumulation_kernels.h"
#include "filters/bmfr/fitting_kernel.h"
#include <cstddef>
#include <cuda_runtime_api.h>

namespace bmfr::cuda {

/// counters[0] += non-finite input values, counters[1] += pixels that lost their history.
template <class H>
void launchAccumulateNoisy(const NoisyAccumulationOf<H>& a, unsigned long long* counters,
                           cudaStream_t stream);
/// out (3 floats per pixel) = phase III's re-modulated colour, before TAA.
template <class H>
void launchAccumulateFitted(const FittedAccumulationOf<H>& a, float* out, cudaStream_t stream);
/// to[i] = from[i] as float, i < n (the fit's output without a fit).
void launchToFloat(const float* from, float* to, long n, cudaStream_t stream);
void launchToFloat(const Half* from, float* to, long n, cudaStream_t stream);
/// accept[i] = sameEmitterTaps(...): no history across an emitter's edge (excludeEmitters).
void launchSameEmitterTaps(uint8_t* accept, const float* previousPixel, const uint8_t* prevEmitter,
                           const uint8_t* emitter, int width, int height, cudaStream_t stream);
/// accept[i] = sameLitTaps(...): no history across a shadow edge (visibilityTaps); prevLit is
/// null on a frame without history.
void launchSameLitTaps(uint8_t* accept, const float* previousPixel, const float* visibility,
                       const uint8_t* prevLit, uint8_t* lit, int width, int height,
                       cudaStream_t stream);
/// fitted = blendSecondFit(fitted, second) where the history length is 1 (secondGrid).
void launchBlendSecondFit(float* fitted, const float* second, const uint8_t* length, long pixels,
                          cudaStream_t stream);
/// storeTileChange(tiles, k, tileHistoryChange(...)) of every tile, from phase I's interleaved
/// record (adaptiveHistory); one thread per tile.
void launchHistoryChange(float* tiles, const float* change, int width, int height, float threshold,
                         float gain, cudaStream_t stream);
/// noise[f * W + k] = regularisationNoise(...) for the frame, on the device.
void launchNoise(float* noise, const Feature* features, int featureCount, int blockPixels,
                 uint32_t seed, uint32_t frame, float amplitude, cudaStream_t stream);

/// How the fit runs on this device for M features and B x B blocks.
struct FitPlan {
    int threads = 256;      ///< team size, a power of two
    size_t sharedBytes = 0; ///< dynamic shared memory per block
    size_t maskBytes = 0;   ///< the emitter mask (and again its stage bits): B^2 bytes, to 16
    bool matrixInShared = true;
    size_t matrixFloats = 0; ///< (M + 3) x B^2: per block, in global scratch when not shared
};
FitPlan planFit(int featureCount, int blockSize);
/// Fits every block of a.grid; `scratch` holds matrixFloats per block when !matrixInShared.
/// With `poorOnly` (history lengths), only the blocks owning a history-poor pixel.
template <class H>
void launchFitBlocks(const BlockFitOf<H>& a, const FitPlan& plan, float* scratch,
                     cudaStream_t stream, const uint8_t* poorOnly = nullptr);

} // namespace bmfr::cuda
