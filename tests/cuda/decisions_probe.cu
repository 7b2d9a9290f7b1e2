// The decisions the conformance suite compares bit for bit, compiled as the library compiles its
// kernels (Kernels.DecisionsWithoutFusedMultiplyAdd): phase I's discard test, blend weight and
// history length, the emitter mask's candidates and steadiness, the firefly clamp. Their PTX must
// hold no fused multiply-add, which rounds once where the reference rounds twice.
#include "filters/bmfr/accumulation_kernels.h"
#include "filters/bmfr/firefly_clamp.h"

namespace bmfr {
__global__ void phaseOne(NoisyAccumulation a, long n, unsigned long long* lost) {
    const long i = blockIdx.x * long(blockDim.x) + threadIdx.x;
    if (i >= n) return;
    int64_t bad = 0;
    if (accumulateNoisyPixel(a, i, bad)) atomicAdd(lost, 1ull);
}
__global__ void emitterMask(const float* accumulated, InputPlanes in, InputModes modes, int n,
                            float threshold, uint8_t* mask) {
    const int i = int(blockIdx.x * blockDim.x + threadIdx.x);
    if (i >= n) return;
    const uint8_t m = maskCandidate(accumulated[i], in, modes, i, threshold);
    mask[i] = steadySample(accumulated[i], accumulated[i + n]) ? m : uint8_t(m | kMaskSeed);
}
__global__ void fireflies(const uint8_t* mask, int B, const float* lum, float threshold,
                          float* scale) {
    const int k = int(threadIdx.x);
    scale[k] = fireflyFade(fireflyScale(mask, B, k, lum[k], threshold), lum[k + B * B]);
}
} // namespace bmfr
