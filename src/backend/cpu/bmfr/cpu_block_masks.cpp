// The firefly clamp and the emitter mask share their BMFR_HD stages (filters/bmfr/) with every
// backend. Compiled without contracted multiply-adds
// (CMakeLists.txt), so that their luminances, and so their decisions, are the reference
// backend's bit for bit; flattened into each path's copy, so that those stages run on its vectors.
#include "backend/cpu/bmfr/cpu_block_masks.h"
#include "backend/cpu/simd.h"

namespace bmfr::cpu {

using namespace simd;

BMFR_SIMD_DISPATCH_FLAT(int, clampAndMaskBlock,
                        (const BlockMaskArgs& a, int bx, int by, float* columns, Scratch& sc),
                        (a, bx, by, columns, sc)) {
    const int B = a.grid.blockSize, W = B * B, M = a.featureCount;
    float* const z[3] = {columns + M * a.stride, columns + (M + 1) * a.stride,
                         columns + (M + 2) * a.stride};
    // The colour columns' luminances eight at a time (the columns are padded past W), in
    // luminance's order of operations, then the buckets of every kMaskStride-th:
    // blockQuantileBucket and clampFireflies without a scalar luminance and bucket per pixel.
    float* lum = sc.lum.data();
    for (int k = 0; k < W; k += 8) {
        const f8 c[3] = {load8(z[0] + k), load8(z[1] + k), load8(z[2] + k)};
        store8(lum + k, luminance8(c));
    }
    const int samples = W / kMaskStride;
    int* buckets = sc.buckets.data();
    const i8 stride = i8{0, 1, 2, 3, 4, 5, 6, 7} * kMaskStride;
    for (int s = 0; s < samples; s += 8)
        std::memcpy(buckets + s,
                    &static_cast<const i8&>(maskBucket8(gather8(lum + s * kMaskStride, stride))),
                    sizeof(i8));
    int* histogram = sc.histogram.data();
    countBuckets(
        samples, [buckets](int s) { return buckets[s]; }, histogram);
    const int quartile = quantileBucket(histogram, samples, kEmitterQuantile);
    int clamped = 0;
    if (a.clampFireflies) {
        // Read for the few pixels the clamp scales only.
        auto length = [&](int k) {
            return blockFadeLength(a.grid, a.emitters, bx, by, k,
                                   [&](long i) { return a.noisy.at(3, size_t(i)); });
        };
        const float threshold = bucketThreshold(medianBucket(histogram, samples), kFireflyRatio);
        clamped = clampFirefliesAbove(
            B, z, sc.mask.data(), threshold, [lum](int k) { return lum[k]; }, length);
    }
    if (!a.emitters.on) return 0;
    if (!clamped) {
        // emitterMask's first test, eight at a time: most blocks have no candidate, and then
        // no mask.
        const float threshold = bucketThreshold(quartile, a.emitters.ratio);
        if (!(threshold > 0.0f)) return 0;
        i8 any{};
        for (int k = 0; k < W; k += 8) any |= (load8(lum + k) > threshold) & firstLanes(W - k);
        if (!anyLane(any)) return 0;
    }
    // The clamp scaled some colours: their luminances are read again.
    return excludeEmitterRows(a.grid, a.in, a.emitters, bx, by, columns, M, a.stride, histogram,
                              sc.mask.data(), quartile, clamped ? nullptr : lum);
}

} // namespace bmfr::cpu
