// Emitters without an emission buffer (BmfrSettings::excludeEmitters). A block fit cannot
// represent a light in view whose normal and position match its surroundings (a ceiling lamp):
// it spreads the light into its dark neighbours, and the bilinear history smears it across the
// light's edge. So:
// - the mask: the block pixels whose accumulated, demodulated luminance is far above the
//   block's lower quartile sit the least squares out when they are, or touch, a pixel whose current
//   sample is as bright and flat (its neighbours' samples agree: an emitter's own light carries
//   no noise), or touch such a pixel that is in turn beside a seed: the history smears a
//   light's edge two pixels wide. A lit surface's noisy samples and fireflies are not flat, and
//   stay in;
// - of those, a pixel whose current sample is above the threshold is the emitter this frame and
//   keeps that sample; the others are the surface beside it and take the fit;
// - a history tap whose emitter bit differs from the pixel's is dropped (phase III and TAA).
// BMFR_HD, in stages that a GPU team runs pixel-parallel and the CPU backends run in loops.
#pragma once
#include "core/color.h"
#include "temporal/pixel_input.h"
#include "temporal/reprojection.h"
#include <cmath>
#include <cstdint>
#include <cstring>

namespace bmfr {

/// The luminance histogram behind the block's median: half-octave buckets from 2^-24 up, with
/// bucket 0 for zero and below and the last bucket open-ended.
inline constexpr int kMaskBuckets = 72;

BMFR_HD int maskBucket(float lum) {
    if (!(lum > 0.0f)) return 0;
    // floor(2 log2(lum) + 49), bucket 1 at 2^-24 and 71 at 2^11, from lum = m 2^e (m in
    // [1/2, 1)) without a logarithm: 2e + 47, plus one in the upper half-octave, m >= 1/sqrt 2.
    // frexp's e and m read from the bits (a call per pixel otherwise): e is the biased exponent
    // less 126, and m orders as its mantissa bits. Subnormals land in bucket 1 either way.
    uint32_t bits;
    std::memcpy(&bits, &lum, sizeof bits);
    const int e = int(bits >> 23) - 126;
    const uint32_t kUpperHalfOctave = 0x3504F3u; // the mantissa bits of 0.70710678f
    const int b = 2 * e + 47 + ((bits & 0x7FFFFFu) >= kUpperHalfOctave ? 1 : 0);
    return b < 1 ? 1 : b > kMaskBuckets - 1 ? kMaskBuckets - 1 : b;
}

/// The upper end of bucket b, so that the median read from the histogram is never below the
/// true one by more than its bucket's width (a factor of sqrt 2).
BMFR_HD float maskBucketTop(int b) {
    return b == 0 ? 0.0f : std::exp2((float(b) + 1.0f - 49.0f) * 0.5f);
}

/// The bucket holding the quantile 1/q of the W counted pixels of a histogram.
BMFR_HD int quantileBucket(const int* histogram, int W, int q) {
    int below = 0;
    for (int b = 0; b < kMaskBuckets; ++b) {
        below += histogram[b];
        if (q * below > W) return b;
    }
    return 0;
}

/// The bucket holding the median of the W counted pixels of a histogram.
BMFR_HD int medianBucket(const int* histogram, int W) {
    return quantileBucket(histogram, W, 2);
}

/// The emitter mask measures "far above" from the block's lower quartile (1/4), not its median:
/// a light may cover more than half of a small block (a 16-pixel block across a lamp 8 pixels
/// tall), and the median would then be the light itself and nothing would be left out.
inline constexpr int kEmitterQuantile = 4;

/// The luminance above which a pixel of the block is a candidate: `ratio` times the top of the
/// reference bucket (a median or a quartile); 0 (no candidate) when that is zero, as in a block
/// mostly black.
BMFR_HD float bucketThreshold(int bucket, float ratio) {
    return bucket == 0 ? 0.0f : ratio * maskBucketTop(bucket);
}

/// bucketThreshold of a histogram of W counted pixels.
BMFR_HD float maskThreshold(const int* histogram, int W, float ratio) {
    return bucketThreshold(medianBucket(histogram, W), ratio);
}

/// Bits of one block pixel's mask byte, set by the stages below in order.
inline constexpr uint8_t kMaskCandidate = 1, kMaskBright = 2, kMaskSeed = 4, kMaskExcluded = 8,
                         kMaskGrown = 16;

/// An emitter's own light carries no noise: its neighbours' current samples agree with its own
/// to within this fraction, where a lit surface's 1-spp samples scatter far wider.
inline constexpr float kEmitterFlatness = 0.02f;

/// An emitter's light is also the same from frame to frame, where a lit surface's 1-spp samples
/// scatter by 10% to 40%. A pixel with history seeds only if its current sample lies within
/// kEmitterSteadiness of its accumulated value, or if it was an emitter in the previous frame
/// (under motion the history smears a light's edge into its neighbours, and the light must not
/// drop out). Without it a lamp-lit block top seeded in some frames and not in others, and its
/// pixels flickered between their noisy sample and the fit. Without history the two values are
/// the same sample, and it passes.
/// A floor lit by a small lamp has nearly noise-free direct light at 1 spp, and at 2% (the
/// flatness) some of its pixels still passed now and then, 0 to 74 a frame on the still room
/// without a light in view; at 0.5% the still rooms flicker 4% and 3% less. The built-in box's
/// lamp stays within 0.2% in most frames (at 0.2% `room-light` lost it in some: 0.226 of the
/// noisy error instead of 0.219), and once found it is kept by the previous frame's emitters.
inline constexpr float kEmitterSteadiness = 0.005f;

BMFR_HD bool steadySample(float sample, float accumulated) {
    return std::fabs(sample - accumulated) <= kEmitterSteadiness * sample;
}

/// Pixel i's current demodulated sample, as phase I read it.
BMFR_HD Vec3 emitterSample(const InputPlanes& in, long i, const InputModes& modes) {
    int64_t ignored = 0; // phase I counted them
    return readColor(in, i, modes, finiteOrZero(load3(in.albedo, i), ignored), ignored);
}

/// Stage 1, pixel k (image pixel i): a candidate when its accumulated luminance is above the
/// threshold, and bright too when its current sample's is (read for candidates only).
BMFR_HD uint8_t maskCandidate(float accumulated, const InputPlanes& in, const InputModes& modes,
                              long i, float threshold) {
    if (!(threshold > 0.0f) || !(accumulated > threshold)) return 0;
    const bool bright = luminance(emitterSample(in, i, modes)) > threshold;
    return uint8_t(kMaskCandidate | (bright ? kMaskBright : 0));
}

/// Whether at least `needed` image neighbours of pixel (x, y) have current samples above the
/// threshold and within kEmitterFlatness of `sample`, its own luminance (across block edges: a
/// light's edge row may be all of it a block holds). lum(u, v) is the luminance of pixel (u, v)'s
/// current sample. Stops reading samples once it knows.
template <class Lum>
BMFR_HD bool flatNeighboursOf(int x, int y, int width, int height, float sample, float threshold,
                              int needed, Lum&& lum) {
    const float tolerance = kEmitterFlatness * sample;
    int flat = 0, left = 8;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            if (!(dx || dy)) continue;
            --left;
            const int u = x + dx, v = y + dy;
            if (u >= 0 && u < width && v >= 0 && v < height) {
                const float s = lum(u, v);
                flat += s > threshold && std::fabs(s - sample) <= tolerance;
            }
            if (flat >= needed) return true;
            if (flat + left < needed) return false;
        }
    return false;
}

/// How many flat neighbours (flatNeighboursOf) a seed needs: four for a new one, three for a
/// pixel that was an emitter in the previous frame. An emitter's inner pixels have eight, its
/// edge and corner pixels five and three. A lamp-lit surface whose direct light is nearly
/// noise-free at 1 spp passes with three now and then, and its pixels flickered between their
/// own sample and the fit (still-camera flicker 0.00030 with three, 0.00024 with four); a
/// light already found keeps its corners.
BMFR_HD int seedNeighbours(bool wasEmitter) {
    return wasEmitter ? 3 : 4;
}

/// flatNeighboursOf image pixel i, reading the samples from the input.
BMFR_HD bool flatNeighbours(const InputPlanes& in, const InputModes& modes, long i, float sample,
                            float threshold, int needed) {
    return flatNeighboursOf(
        int(i % in.width), int(i / in.width), in.width, in.height, sample, threshold, needed,
        [&](int u, int v) { return luminance(emitterSample(in, long(v) * in.width + u, modes)); });
}

/// Stage 2, pixel k (image pixel i, accumulated luminance `accumulated`, `was` an emitter in
/// the previous frame): a bright candidate whose sample is steady (or was an emitter) and
/// seedNeighbours(was) neighbours share seeds an emitter. A lit surface's noisy samples, and
/// fireflies, do not.
BMFR_HD uint8_t maskSeed(uint8_t m, const InputPlanes& in, const InputModes& modes, long i,
                         float threshold, float accumulated, bool was) {
    const uint8_t both = kMaskCandidate | kMaskBright;
    if ((m & both) != both) return 0;
    const float s = luminance(emitterSample(in, i, modes));
    return (was || steadySample(s, accumulated)) &&
                   flatNeighbours(in, modes, i, s, threshold, seedNeighbours(was))
               ? kMaskSeed
               : 0;
}

/// The eight neighbours of block pixel k inside the block with `bit` set in `mask`.
BMFR_HD int maskNeighbours(const uint8_t* mask, int B, int k, uint8_t bit) {
    const int x = k % B, y = k / B;
    int n = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int u = x + dx, v = y + dy;
            if ((dx || dy) && u >= 0 && u < B && v >= 0 && v < B && (mask[v * B + u] & bit)) ++n;
        }
    return n;
}

/// Stage 3, block pixel k: a candidate that is a seed or touches one in the block sits the fit
/// out. Those that only touch one are mostly the surface beside the emitter, which the history
/// smeared it into.
BMFR_HD uint8_t maskExcluded(const uint8_t* mask, int B, int k) {
    const uint8_t m = mask[k];
    if (!(m & kMaskCandidate)) return 0;
    return (m & kMaskSeed) || maskNeighbours(mask, B, k, kMaskSeed) > 0 ? kMaskExcluded : 0;
}

/// Stage 4, block pixel k: a candidate that touches an excluded pixel sits the fit out too (its
/// own bit, so that the step is one pixel whatever the order). The smear past a light's edge is
/// two pixels wide, and its outer ring, left in, lifts a small block's fit around the light.
BMFR_HD uint8_t maskGrown(const uint8_t* mask, int B, int k) {
    const uint8_t m = mask[k];
    if (!(m & kMaskCandidate) || (m & kMaskExcluded)) return 0;
    return maskNeighbours(mask, B, k, kMaskExcluded) > 0 ? kMaskGrown : 0;
}

/// Stage 5, block pixel k: the grown pixels join the excluded ones.
BMFR_HD uint8_t maskWithGrowth(uint8_t m) {
    return m & kMaskGrown ? uint8_t(m | kMaskExcluded) : m;
}

/// Whether an excluded pixel is the emitter this frame (it then keeps its current sample) or
/// the surface beside it (it takes the fit).
BMFR_HD bool maskEmitter(uint8_t m) {
    return (m & kMaskExcluded) && (m & kMaskBright);
}

/// The largest block (64 x 64) whose current samples emitterMask keeps while it tests seeds.
inline constexpr int kMaskCachePixels = 64 * 64;

/// A block with more than W / kMaskDenseCandidates candidates reads every current sample up
/// front, not as its seed tests ask for them.
inline constexpr int kMaskDenseCandidates = 8;

/// The block's median is read from every kMaskStride-th pixel: a bucket is a factor of sqrt 2
/// wide, and a quarter of the block places the median as well.
inline constexpr int kMaskStride = 4;

/// The histogram of n samples whose buckets are bucket(0) .. bucket(n - 1).
template <class Bucket> BMFR_HD void countBuckets(int n, Bucket&& bucket, int* histogram) {
    for (int b = 0; b < kMaskBuckets; ++b) histogram[b] = 0;
    for (int s = 0; s < n; ++s) ++histogram[bucket(s)];
}

/// The quantile-1/q bucket of a block of W pixels (a multiple of kMaskStride) from
/// accumulated(k); `histogram` keeps the count.
template <class Accumulated>
BMFR_HD int blockQuantileBucket(int W, Accumulated&& accumulated, int* histogram, int q) {
    countBuckets(
        W / kMaskStride, [&](int s) { return maskBucket(accumulated(s * kMaskStride)); },
        histogram);
    return quantileBucket(histogram, W / kMaskStride, q);
}

/// The median bucket of a block of W pixels from accumulated(k).
template <class Accumulated>
BMFR_HD int blockMedianBucket(int W, Accumulated&& accumulated, int* histogram) {
    return blockQuantileBucket(W, accumulated, histogram, 2);
}

/// The median threshold of a block of W pixels from accumulated(k).
template <class Accumulated>
BMFR_HD float blockThreshold(int W, float ratio, Accumulated&& accumulated, int* histogram) {
    return bucketThreshold(blockMedianBucket(W, accumulated, histogram), ratio);
}

/// The emitter mask's threshold of a block of W pixels: `ratio` times its lower quartile.
template <class Accumulated>
BMFR_HD float emitterThreshold(int W, float ratio, Accumulated&& accumulated, int* histogram) {
    return bucketThreshold(blockQuantileBucket(W, accumulated, histogram, kEmitterQuantile), ratio);
}

/// Current samples' luminances a backend already has (the CPU's phase I writes them for the
/// adaptive history), for SampleLuminance.
struct KnownSamples {
    const float* values = nullptr; ///< max(luminance, 0) of image pixels [from, to), or null
    long from = 0, to = 0;
};

/// The luminance of image pixel i's current demodulated sample, as emitterMask reads it: from
/// the input, or from `known` where it covers the pixel, with the same decisions.
struct SampleLuminance {
    const InputPlanes& in;
    InputModes modes;
    KnownSamples known = {};
    BMFR_HD float operator()(long i) const {
        // A negative luminance read as 0 decides the same: every test needs it above a positive
        // threshold.
        if (known.values && i >= known.from && i < known.to) return known.values[i];
        return luminance(emitterSample(in, i, modes));
    }
    /// Whether pixels [first, last) are all read from `known`.
    BMFR_HD bool knows(long first, long last) const {
        return known.values && first >= known.from && last <= known.to;
    }
};

/// The whole mask of a B x B block, one stage after another. sample(i) is the luminance of
/// image pixel i's current sample (SampleLuminance), accumulated(k) the accumulated
/// luminance of block pixel k, pixel(k) its image pixel and was(i) whether image pixel i was
/// an emitter in the previous frame (maskSeed); `quartile` is the block's
/// lower-quartile bucket when known (clampFireflies leaves it unchanged), else -1; `origin` is
/// pixel(0) when the block lies inside the image (pixel(k) is then origin + (k / B) rows + k % B),
/// else -1. Returns the
/// number of excluded pixels; the mask means something only when that is above 0 (most blocks
/// have no candidate, and it is not written).
template <class Accumulated, class Pixel, class Was>
BMFR_HD int emitterMask(int B, float ratio, const SampleLuminance& sample,
                        Accumulated&& accumulated, Pixel&& pixel, Was&& was, int* histogram,
                        uint8_t* mask, int quartile = -1, long origin = -1) {
    const InputPlanes& in = sample.in;
    const int W = B * B;
    if (quartile < 0) quartile = blockQuantileBucket(W, accumulated, histogram, kEmitterQuantile);
    const float threshold = bucketThreshold(quartile, ratio);
    if (!(threshold > 0.0f)) return 0;
    // Stage 1's first half for every pixel at once (it vectorises), so that the pass below
    // visits the candidates only.
    int candidates = 0;
    for (int k = 0; k < W; ++k) {
        const uint8_t c = accumulated(k) > threshold ? kMaskCandidate : 0;
        mask[k] = c;
        candidates += c;
    }
    if (candidates == 0) return 0;
    // Without a seed nothing is excluded: most blocks with a candidate stop there (a lit
    // patch's noisy samples).
    // Stages 1 and 2 (maskCandidate, maskSeed) in one pass: a pixel's current sample is read
    // once for its own tests and, in a block inside the image, once for all its neighbours' seed
    // tests too (a lit patch's bright candidates are each other's neighbours). pixel(k)
    // (divisions, and mirroring at the border) only for candidates.
    const bool inside = origin >= 0 && W <= kMaskCachePixels;
    float samples[kMaskCachePixels];
    const int ox = inside ? int(origin % in.width) : 0, oy = inside ? int(origin / in.width) : 0;
    // Samples a backend already has need no cache.
    const bool cached = inside && !sample.knows(origin, origin + long(B - 1) * in.width + B);
    if (cached && kMaskDenseCandidates * candidates > W) {
        // Many candidates, as in a block without history (one noisy sample per pixel): nearly
        // every sample is read, so all are, in one loop without a cache test per lookup.
        for (int ly = 0; ly < B; ++ly)
            for (int lx = 0; lx < B; ++lx)
                samples[ly * B + lx] = sample(long(oy + ly) * in.width + ox + lx);
    } else if (cached) {
        for (int k = 0; k < W; ++k) samples[k] = -1.0f; // a finite sample's luminance is >= 0
    }
    auto lum = [&](int u, int v) {
        const int lx = u - ox, ly = v - oy;
        const long i = long(v) * in.width + u;
        if (!cached || lx < 0 || lx >= B || ly < 0 || ly >= B) return sample(i);
        float& s = samples[ly * B + lx];
        if (!(s >= 0.0f)) s = sample(i);
        return s;
    };
    int seeds = 0;
    for (int ly = 0, k = 0; ly < B; ++ly)
        for (int lx = 0; lx < B; ++lx, ++k) {
            if (lx % 8 == 0 && lx + 8 <= B) { // eight pixels without a candidate at once
                uint64_t none;
                std::memcpy(&none, mask + k, sizeof none);
                if (!none) {
                    lx += 7, k += 7;
                    continue;
                }
            }
            if (!mask[k]) continue;
            const float acc = accumulated(k);
            int x = ox + lx, y = oy + ly; // inside the image
            if (!inside) {
                const long i = pixel(k);
                x = int(i % in.width), y = int(i / in.width);
            }
            const float s = lum(x, y);
            if (!(s > threshold)) continue;
            mask[k] |= kMaskBright;
            const bool before = was(long(y) * in.width + x);
            const bool steady = before || steadySample(s, acc);
            if (steady && flatNeighboursOf(x, y, in.width, in.height, s, threshold,
                                           seedNeighbours(before), lum))
                mask[k] |= kMaskSeed, ++seeds;
        }
    if (seeds == 0) return 0;
    for (int k = 0; k < W; ++k) mask[k] |= maskExcluded(mask, B, k);
    for (int k = 0; k < W; ++k) mask[k] |= maskGrown(mask, B, k);
    int excluded = 0;
    for (int k = 0; k < W; ++k) {
        mask[k] = maskWithGrowth(mask[k]);
        excluded += (mask[k] & kMaskExcluded) != 0;
    }
    return excluded;
}

/// Phase I cannot ask whether a pixel is an emitter (the fit decides that later), but a pixel
/// whose current sample is below this share of an emitter tap's accumulated value is not that
/// light: an emitter's own sample carries no noise and a pixel on its edge covers at least part
/// of it.
inline constexpr float kEmitterTapShare = 0.5f;

/// Phase I's accepted taps of a pixel whose current demodulated sample has luminance `sample`,
/// less the taps that were emitter pixels in the previous frame (prevClass[j] & bit) and are
/// more than 1 / kEmitterTapShare times as bright (tapLuminance(j): their accumulated value).
/// Without it a light's history smears into the dim surface around it under camera motion, by
/// more than the emitter mask's two pixels of growth, and the fit spreads that over the block:
/// a halo.
template <class TapLuminance>
BMFR_HD uint8_t phaseOneEmitterTaps(uint8_t accept, const BilinearFootprint& fp,
                                    const uint8_t* prevClass, uint8_t bit, float sample, int width,
                                    TapLuminance&& tapLuminance) {
    for (int t = 0; t < 4; ++t) {
        if (!(accept & (1u << t))) continue;
        const long j = long(tapY(fp, t)) * width + tapX(fp, t);
        if ((prevClass[j] & bit) && sample < kEmitterTapShare * tapLuminance(j))
            accept &= uint8_t(~(1u << t));
    }
    return accept;
}

/// Phase I's accepted taps of a pixel less those whose emitter bit in the previous frame differs
/// from the pixel's own, so that no history crosses an emitter's edge.
BMFR_HD uint8_t sameEmitterTaps(uint8_t accept, Vec2 previousPixel, const uint8_t* prevEmitter,
                                uint8_t own, int width) {
    if (!accept) return 0;
    const BilinearFootprint fp = bilinearFootprint(previousPixel);
    for (int t = 0; t < 4; ++t)
        if ((accept & (1u << t)) && prevEmitter[long(tapY(fp, t)) * width + tapX(fp, t)] != own)
            accept &= uint8_t(~(1u << t));
    return accept;
}

} // namespace bmfr
