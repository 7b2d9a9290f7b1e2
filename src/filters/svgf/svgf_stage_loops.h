// SVGF's per-pixel stages, each written once as a loop of its BMFR_HD kernels on an executor
// (core/executor.h): the reference backend runs them on the host's threads, the CUDA backend as
// kernels. The reference's accumulation and variance go by rows instead, so that the CPU
// backend can put its eight-wide rows in their place (reference_svgf_stages.h).
#pragma once
#include "core/executor.h"
#include "filters/svgf/svgf_kernels.h"
#include "filters/svgf/svgf_passes.h"
#include "temporal/modulation.h"

namespace bmfr {

/// The temporal accumulation; adds the non-finite inputs to `nonFinite` and, with a history,
/// the pixels that kept no tap of it to `discarded`.
template <class Exec>
void svgfAccumulateStage(const Exec& e, const SvgfFrame& f, FrameCounter nonFinite,
                         FrameCounter discarded) {
    e.forEachIndex(
        long(f.width) * f.height, BMFR_LAMBDA(long i) {
            int64_t bad = 0;
            svgfAccumulatePixel(f, i, bad);
            nonFinite.add(bad);
            discarded.add(f.previous.valid && f.accept[i] == 0 ? 1 : 0);
        });
}

/// The depth gradient the a-trous weights use.
template <class Exec> void svgfDepthGradientStage(const Exec& e, const SvgfFrame& f) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { svgfDepthGradientPixel(f, x, y); });
}

/// The variance estimate into `filtered` (4 floats per pixel) and `variance`.
template <class Exec>
void svgfVarianceStage(const Exec& e, const SvgfFrame& f, const SvgfSettings& s, float* filtered,
                       float* variance) {
    e.forEachPixel(
        f.width, f.height,
        BMFR_LAMBDA(int x, int y) { svgfVariancePixel(f, s, x, y, filtered, variance); });
}

/// One a-trous level, level.in to level.out.
template <class Exec>
void svgfAtrousStage(const Exec& e, const AtrousLevel& level, const SvgfSettings& s) {
    e.forEachPixel(
        level.width, level.height, BMFR_LAMBDA(int x, int y) { svgfAtrousPixel(level, s, x, y); });
}

/// The step-1 level's colour fed back as the colour history (n pixels).
template <class Exec>
void svgfKeepLevelStage(const Exec& e, const float* level, float* color, long n) {
    e.forEachIndex(
        n, BMFR_LAMBDA(long i) { store3(color, i, load3Stride4(level, i)); });
}

/// The a-trous levels from filtered[0] (an image pair, 4 floats per pixel), with `level`'s
/// guides: the step-1 level fed back as the colour history `color`. Returns the last level's
/// index in `filtered`.
template <class Exec, class F>
int svgfAtrousLevelsStage(const Exec& e, const SvgfSettings& s, AtrousLevel level, F (&filtered)[2],
                          float* color) {
    return runAtrousLevels(
        s,
        [&](int from, int to, int step) {
            level.in = filtered[from].data(), level.out = filtered[to].data();
            level.step = step;
            svgfAtrousStage(e, level, s);
        },
        [&](int k) { svgfKeepLevelStage(e, filtered[k].data(), color, filtered[k].pixelCount()); });
}

/// The last level re-modulated into `out`.
template <class Exec>
void svgfRemodulateStage(const Exec& e, const float* level, const InputPlanes& in,
                         float albedoEpsilon, float* out) {
    e.forEachIndex(
        long(in.width) * in.height, BMFR_LAMBDA(long i) {
            store3(out, i, remodulatePixel(load3Stride4(level, i), in, i, true, albedoEpsilon));
        });
}

} // namespace bmfr
