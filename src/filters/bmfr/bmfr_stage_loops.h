// BMFR's per-pixel stages, each written once as a loop of its BMFR_HD kernels on an executor
// (core/executor.h): the reference backend runs them on the host's threads, the CUDA backend as
// kernels. The fit is each backend's own (the reference's fitBlock per block, CUDA's team fit).
#pragma once
#include "core/executor.h"
#include "filters/bmfr/accumulation_kernels.h"
#include "filters/bmfr/regularisation_noise.h"
#include "filters/bmfr/second_grid.h"
#include "filters/bmfr/visibility_taps.h"

namespace bmfr {

/// Phase I; adds the non-finite inputs to `nonFinite` and the pixels that lost their history
/// to `lost`.
template <class Exec, class H>
void bmfrAccumulateNoisyStage(const Exec& e, const NoisyAccumulationOf<H>& a,
                              FrameCounter nonFinite, FrameCounter lost) {
    e.forEachIndex(
        long(a.width) * a.height, BMFR_LAMBDA(long i) {
            int64_t bad = 0;
            const bool gone = accumulateNoisyPixel(a, i, bad);
            nonFinite.add(bad);
            lost.add(gone ? 1 : 0);
        });
}

/// The frame's regularisation noise: noise[f * W + k] for M features and W block pixels.
template <class Exec>
void bmfrNoiseStage(const Exec& e, float* noise, const Feature* features, int M, int W,
                    uint32_t seed, uint32_t frame, float amplitude) {
    e.forEachIndex(
        long(M) * W, BMFR_LAMBDA(long i) {
            const int f = int(i / W), k = int(i % W);
            noise[i] = regularisationNoise(seed, frame, f, k, amplitude,
                                           features[f].source == FeatureSource::One);
        });
}

/// Without a fit: phase I's colour as the fitted colour (n floats).
template <class Exec, class H>
void bmfrUnfittedStage(const Exec& e, const H* accumulated, float* fitted, long n) {
    e.forEachIndex(
        n, BMFR_LAMBDA(long i) { fitted[i] = float(accumulated[i]); });
}

/// fitted = blendSecondFit(fitted, second) where the history is poor (secondGrid).
template <class Exec>
void bmfrBlendSecondFitStage(const Exec& e, float* fitted, const float* second,
                             const uint8_t* length, long n) {
    e.forEachIndex(
        n, BMFR_LAMBDA(long i) {
            if (historyPoor(length[i]))
                for (int c = 0; c < 3; ++c)
                    fitted[3 * i + c] = blendSecondFit(fitted[3 * i + c], second[3 * i + c]);
        });
}

/// accept = sameEmitterTaps(...): no history across an emitter's edge (excludeEmitters).
template <class Exec>
void bmfrSameEmitterTapsStage(const Exec& e, uint8_t* accept, const float* pp,
                              const uint8_t* prevEmitter, const uint8_t* emitter, int width,
                              int height) {
    e.forEachIndex(
        long(width) * height, BMFR_LAMBDA(long i) {
            accept[i] = sameEmitterTaps(accept[i], {pp[2 * i], pp[2 * i + 1]}, prevEmitter,
                                        emitter[i], width);
        });
}

/// accept = sameLitTaps(...): no history across a shadow edge (visibilityTaps); prevLit is null
/// on a frame without history.
template <class Exec>
void bmfrSameLitTapsStage(const Exec& e, uint8_t* accept, const float* pp, const float* visibility,
                          const uint8_t* prevLit, uint8_t* lit, int width, int height) {
    e.forEachIndex(
        long(width) * height, BMFR_LAMBDA(long i) {
            accept[i] = sameLitTaps(accept[i], {pp[2 * i], pp[2 * i + 1]}, visibility, prevLit, lit,
                                    i, width);
        });
}

/// storeTileChange of every tile's tileHistoryChange (adaptiveHistory), from phase I's record.
template <class Exec>
void bmfrHistoryChangeStage(const Exec& e, float* tiles, const float* change, int width, int height,
                            float threshold, float gain) {
    const int tilesX = changeTilesX(width);
    e.forEachIndex(
        long(tilesX) * changeTilesY(height), BMFR_LAMBDA(long k) {
            storeTileChange(tiles, k,
                            tileHistoryChange(change, change + 1, 2, width, height, int(k % tilesX),
                                              int(k / tilesX), threshold, gain));
        });
}

/// Phase III into `out` (3 floats per pixel): the re-modulated colour, before TAA.
template <class Exec, class H>
void bmfrAccumulateFittedStage(const Exec& e, const FittedAccumulationOf<H>& a, float* out) {
    e.forEachIndex(
        long(a.width) * a.in.height,
        BMFR_LAMBDA(long i) { store3(out, i, accumulateFittedPixel(a, i)); });
}

} // namespace bmfr
