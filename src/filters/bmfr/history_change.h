// Adaptive history (BmfrSettings::adaptiveHistory): BMFR's histories are long (phase III is a
// plain mean of up to ten frames), so where the lighting changes (a moving light, a light
// switched on) the output lags it for frames. Here a 32x32 tile whose current samples' mean has
// left its reprojected phase I history's mean by more than their noise explains gets a shorter
// history, in proportion to the change (as A-SVGF's temporal gradient, but from tile means, as
// this input has no re-shaded samples). Where nothing changed the history stays the paper's.
// A tile's mean moves by a few percent per frame under a moving light while its history lags
// by the sum of those steps, so the change is amplified (BmfrSettings::historyChangeGain).
// - phase I records each pixel's sample and history luminance (recordHistoryChange);
// - one pass reduces them per tile (tileHistoryChange), in a fixed order that eight lanes keep,
//   and a weak change counts only when the tile also changed in the frame before
//   (storeTileChange);
// - phase III blends with the larger weight and shortens the stored history length, which the
//   next frame's phase I and phase III read (adaptHistory).
// BMFR_HD: one source for every backend.
#pragma once
#include "core/color.h"
#include "core/vec.h"
#include <cmath>
#include <cstdint>

namespace bmfr {

/// Edge of the square, image-aligned tiles whose means are compared, in pixels: 1024 samples
/// make a tile's mean some 30 times steadier than one sample, at 32 pixels of resolution. A
/// multiple of 8, so that eight neighbouring pixels of a row share a tile.
inline constexpr int kChangeTile = 32;

/// A tile with fewer pixels with history than this has no change measured (its pixels' histories
/// are short already).
inline constexpr int kChangeMinPixels = 64;

BMFR_HD int changeTilesX(int width) {
    return (width + kChangeTile - 1) / kChangeTile;
}
BMFR_HD int changeTilesY(int height) {
    return (height + kChangeTile - 1) / kChangeTile;
}

/// Each tile keeps two values (storeTileChange): the change in effect, which phase III and the
/// next frame's phase I read, and the change measured this frame.
inline constexpr int kChangeTileValues = 2;

/// The floats of a w x h frame's tile record.
BMFR_HD long changeTileFloats(int width, int height) {
    return long(kChangeTileValues) * changeTilesX(width) * changeTilesY(height);
}

/// Phase I, pixel i: its current sample's luminance and its reprojected history's, at
/// sample[i * step] and history[i * step]; a pixel without history stores -1 for the latter and
/// is not counted.
BMFR_HD void recordHistoryChange(float* sample, float* history, long step, long i, Vec3 s, Vec3 h,
                                 bool hasHistory) {
    const float ls = luminance(s), lh = luminance(h);
    sample[i * step] = ls > 0.0f ? ls : 0.0f;
    history[i * step] = !hasHistory ? -1.0f : lh > 0.0f ? lh : 0.0f;
}

/// A tile's sums run in kChangeLanes interleaved partial sums (column x of the tile adds to lane
/// x % kChangeLanes, row by row), joined by laneTotal: the order an eight-wide CPU loop keeps,
/// so every backend gets the same bits.
inline constexpr int kChangeLanes = 8;

BMFR_HD float laneTotal(const float* v) {
    return ((v[0] + v[1]) + (v[2] + v[3])) + ((v[4] + v[5]) + (v[6] + v[7]));
}

/// The change from a tile's sums over its n pixels with history: 0 (none) to 1 (the history is
/// no longer this light). How far the mean sample is from the mean history, less `threshold`
/// standard errors of the samples' mean, as a fraction of the larger mean, times `gain`.
BMFR_HD float changeFromSums(int n, float sum, float squares, float past, float threshold,
                             float gain) {
    if (n < kChangeMinPixels) return 0.0f;
    const float mean = sum / float(n), meanHistory = past / float(n);
    const float variance = squares / float(n) - mean * mean;
    const float standardError = variance > 0.0f ? std::sqrt(variance / float(n)) : 0.0f;
    const float excess = std::fabs(mean - meanHistory) - threshold * standardError;
    const float scale = mean > meanHistory ? mean : meanHistory;
    if (!(excess > 0.0f) || !(scale > 0.0f)) return 0.0f;
    const float change = gain * excess / scale;
    return change < 1.0f ? change : 1.0f;
}

/// The change of tile (tx, ty) (changeFromSums), from recordHistoryChange's values.
BMFR_HD float tileHistoryChange(const float* sample, const float* history, long step, int width,
                                int height, int tx, int ty, float threshold, float gain) {
    const int x0 = tx * kChangeTile, y0 = ty * kChangeTile;
    const int x1 = x0 + kChangeTile < width ? x0 + kChangeTile : width;
    const int y1 = y0 + kChangeTile < height ? y0 + kChangeTile : height;
    int n = 0;
    float sum[kChangeLanes] = {}, squares[kChangeLanes] = {}, past[kChangeLanes] = {};
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const long i = (long(y) * width + x) * step;
            const float s = sample[i], h = history[i];
            if (h < 0.0f) continue;
            const int lane = (x - x0) % kChangeLanes;
            ++n;
            sum[lane] += s;
            squares[lane] += s * s;
            past[lane] += h;
        }
    return changeFromSums(n, laneTotal(sum), laneTotal(squares), laneTotal(past), threshold, gain);
}

/// A measured change of at most this much counts only if the tile's change measured in the
/// previous frame was above 0 too. Noise alone shows a change in one tile in twenty, rarely two
/// frames running, and each one shortened a 32-pixel tile's history for a frame: on the still
/// room without a light in view, a tile in sixteen a frame (up to 0.36), and 4% of the preset's
/// flicker. A light that moves changes its tiles frame after frame, and one switched or dimmed
/// changes them by more than this at once.
inline constexpr float kChangeConfirm = 0.5f;

/// The change in effect for a tile that measured `measured` this frame and `previous` in the
/// frame before.
BMFR_HD float confirmedChange(float measured, float previous) {
    return measured > kChangeConfirm || previous > 0.0f ? measured : 0.0f;
}

/// Records tile k's change measured this frame (tileHistoryChange) and the change in effect.
BMFR_HD void storeTileChange(float* tiles, long k, float measured) {
    float* tile = tiles + long(kChangeTileValues) * k;
    tile[0] = confirmedChange(measured, tile[1]);
    tile[1] = measured;
}

/// The change in effect of pixel (x, y)'s tile.
BMFR_HD float pixelHistoryChange(const float* tiles, int width, int x, int y) {
    const long k = long(y / kChangeTile) * changeTilesX(width) + x / kChangeTile;
    return tiles[long(kChangeTileValues) * k];
}

/// Phase III, the blend weight of a pixel of change `lambda`: (1 - lambda) weight + lambda, as
/// A-SVGF's; unchanged at lambda 0.
BMFR_HD float adaptedBlendWeight(float weight, float lambda) {
    return lambda > 0.0f ? weight + lambda * (1.0f - weight) : weight;
}

/// Phase I of the next frame, a pixel whose tile changed by `lambda`: its reprojected history
/// length (samples) at most what phase III's adapted weight averages, so that phase I follows the
/// change too and phase III keeps the shorter history: 1 / (minAlpha + lambda (1 - minAlpha))
/// samples, the new one included, with minAlpha phase III's (BmfrSettings::secondBlendAlpha).
/// Unchanged at lambda 0 (the paper's lengths).
BMFR_HD float shortenedHistory(float samples, float lambda, float minAlpha) {
    if (!(lambda > 0.0f)) return samples;
    const float frames = 1.0f / (minAlpha + lambda * (1.0f - minAlpha));
    return samples < frames - 1.0f ? samples : frames - 1.0f;
}

} // namespace bmfr
