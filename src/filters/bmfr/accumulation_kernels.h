// BMFR's two temporal accumulations, one pixel at a time (paper section 4.1 and 4.3): phase I
// reprojects and accumulates the noisy colour and records its decisions; phase III reuses them
// for the fitted colour. BMFR_HD: the reference backend loops over these; the CPU backend's
// eight-wide versions (backend/cpu/bmfr/) mirror them.
#pragma once
#include "core/half.h"
#include "filters/bmfr/emitter_exclusion.h"
#include "filters/bmfr/history_change.h"
#include "filters/bmfr/visibility_taps.h"
#include "temporal/blend_weights.h"
#include "temporal/history.h"
#include "temporal/modulation.h"
#include "temporal/pixel_input.h"
#include "temporal/reprojection.h"

namespace bmfr {

/// Phase I's buffers for one frame: packed images of the backend's (3 floats per pixel unless
/// said), `prev*` from the previous frame's slot. H is how the history planes that halfHistory
/// rounds are stored: float, or Half where halfHistory is on and the bytes matter (CUDA).
template <class H> struct NoisyAccumulationOf {
    InputPlanes in;
    InputModes modes;
    PreviousFrame previous;
    DiscardLimits limits;
    float minAlpha = 0.2f;   ///< BmfrSettings::firstBlendAlpha
    bool accumulate = true;  ///< StageSwitches::firstAccumulation
    bool halfHistory = true; ///< BmfrSettings::halfHistory: normals and colour stored as half
    int width = 0, height = 0;
    H* normal = nullptr; ///< sanitised features, for the next frame's discard test
    float* position = nullptr;
    const H* prevNormal = nullptr;
    const float* prevPosition = nullptr;
    const H* prevNoisy = nullptr;
    const uint8_t* prevLength = nullptr;
    H* noisy = nullptr;             ///< accumulated demodulated colour
    uint8_t* length = nullptr;      ///< history length, 1..255
    float* previousPixel = nullptr; ///< 2 floats: continuous pixel in the previous frame
    uint8_t* accept = nullptr;      ///< accepted taps, bit i = tap i
    // BmfrSettings::adaptiveHistory (filters/bmfr/history_change.h): recordHistoryChange's
    // output, interleaved, and the previous frame's tile changes with phase III's minAlpha.
    float* change = nullptr;
    const float* prevChangeTiles = nullptr;
    float secondMinAlpha = 0.1f;
    /// BmfrSettings::excludeEmitters: the previous frame's emitter bits (phaseOneEmitterTaps).
    const uint8_t* prevEmitter = nullptr;
    /// BmfrSettings::visibilityTaps, with a visibility buffer: this frame's visibility and the
    /// previous frame's lit classes (sameEmitterTaps on lit classes).
    const float* visibility = nullptr;
    const uint8_t* prevLit = nullptr;
};
using NoisyAccumulation = NoisyAccumulationOf<float>;

/// Phase I of pixel i. Returns true when the pixel had a history and lost all of it.
template <class H>
BMFR_HD bool accumulateNoisyPixel(const NoisyAccumulationOf<H>& a, long i, int64_t& bad) {
    const PixelInput px = readPixel(a.in, i, a.modes, bad);
    const Vec3 n = px.normal, p = px.position;
    Vec3 c = px.color;
    store3(a.normal, i, a.halfHistory ? roundToHalf(n) : n);
    store3(a.position, i, p);

    uint8_t accept = 0;
    float samples = 0.0f, blend = 1.0f;
    bool reprojected = false; // some history tap accepted
    Vec3 old{};
    const PreviousFrame& prev = a.previous;
    // Without a previous pixel, was.pixel stays out of every image: TAA and phase III skip it.
    PreviousSurface was;
    if (findPreviousSurface(a.in, i, int(i % a.width), int(i / a.width), p, n, prev, bad, was)) {
        const BilinearFootprint fp = bilinearFootprint(was.pixel);
        accept = acceptTaps(fp, was.position, was.normal, a.prevPosition, a.prevNormal, a.width,
                            a.height, a.limits);
        if (a.prevEmitter)
            accept = phaseOneEmitterTaps(accept, fp, a.prevEmitter, 1, luminance(c), a.width,
                                         [&](long j) { return luminance(load3(a.prevNoisy, j)); });
        // No history across a shadow edge either (visibilityTaps, as phase III's sameLitTaps).
        if (a.prevLit)
            accept =
                sameEmitterTaps(accept, was.pixel, a.prevLit, litClass(a.visibility, i), a.width);
        const float total = gatherAccepted(fp, accept, a.width, [&](long j, float wt) {
            old += wt * load3(a.prevNoisy, j);
            samples += wt * float(a.prevLength[j]);
        });
        if (total > 0.0f) {
            reprojected = true;
            old = old / total;
            samples /= total;
            if (a.prevChangeTiles)
                samples = shortenedHistory(samples,
                                           pixelHistoryChange(a.prevChangeTiles, a.width,
                                                              int(i % a.width), int(i / a.width)),
                                           a.secondMinAlpha);
            blend = firstBlendWeight(samples, a.minAlpha);
        }
    }
    a.length[i] = blend < 1.0f ? nextHistoryLength(samples) : 1;
    if (a.change) recordHistoryChange(a.change, a.change + 1, 2, i, c, old, reprojected);
    if (a.accumulate && blend < 1.0f) c = lerp(old, c, blend);
    store3(a.noisy, i, a.halfHistory ? roundToHalf(c) : c);
    a.previousPixel[2 * i] = was.pixel.x;
    a.previousPixel[2 * i + 1] = was.pixel.y;
    a.accept[i] = accept;
    return prev.valid && accept == 0;
}

/// Phase III's buffers for one frame (H as in NoisyAccumulationOf).
template <class H> struct FittedAccumulationOf {
    InputPlanes in;
    bool accumulate = true; ///< a history exists and StageSwitches::secondAccumulation
    bool remodulate = true; ///< demodulated on input (by us or by the renderer)
    float albedoEpsilon = 0.001f;
    float minAlpha = 0.1f;   ///< BmfrSettings::secondBlendAlpha
    bool halfHistory = true; ///< BmfrSettings::halfHistory: the history stored as half
    int width = 0;
    const float* fitted = nullptr;
    const H* prevAccumulated = nullptr;
    const float* previousPixel = nullptr; ///< phase I's
    const uint8_t* accept = nullptr;      ///< phase I's
    const uint8_t* length = nullptr;      ///< phase I's
    H* accumulated = nullptr;             ///< the next frame's history (demodulated)
    const float* changeTiles = nullptr;   ///< BmfrSettings::adaptiveHistory: tileHistoryChange's
};
using FittedAccumulation = FittedAccumulationOf<float>;

/// Phase III of pixel i, with phase I's reprojection and discard decisions (no second test).
/// Stores the history and returns the re-modulated colour with the emission added, for TAA.
template <class H> BMFR_HD Vec3 accumulateFittedPixel(const FittedAccumulationOf<H>& a, long i) {
    Vec3 c = load3(a.fitted, i);
    const uint8_t accept = a.accept[i];
    if (a.accumulate && accept) {
        const Vec2 pp{a.previousPixel[2 * i], a.previousPixel[2 * i + 1]};
        Vec3 old{};
        const float total =
            gatherAccepted(bilinearFootprint(pp), accept, a.width,
                           [&](long j, float wt) { old += wt * load3(a.prevAccumulated, j); });
        if (total > 0.0f) {
            float weight = secondBlendWeight(a.length[i], a.minAlpha);
            if (a.changeTiles)
                weight = adaptedBlendWeight(
                    weight,
                    pixelHistoryChange(a.changeTiles, a.width, int(i % a.width), int(i / a.width)));
            c = lerp(old / total, c, weight);
        }
    }
    store3(a.accumulated, i, a.halfHistory ? roundToHalf(c) : c);
    return remodulatePixel(c, a.in, i, a.remodulate, a.albedoEpsilon);
}

} // namespace bmfr
