// Mara 2017's stages, each written once as loops of its stage bodies (mara_stages.h) on an
// executor (core/executor.h): the reference backend runs them on the host's threads, the CUDA
// backend as kernels, and the CPU backend replaces those it has faster.
#pragma once
#include "core/executor.h"
#include "filters/mara2017/mara_stages.h"

namespace bmfr {

/// The input pass and stage 3 (matte temporal); adds the non-finite inputs to `nonFinite`.
template <class Exec>
void maraMatteTemporalStage(const Exec& e, const MaraFrame& f, FrameCounter nonFinite) {
    e.forEachIndex(
        long(f.width) * f.height, BMFR_LAMBDA(long i) {
            int64_t bad = 0;
            maraInputPixel(f, i, bad);
            nonFinite.add(bad);
        });
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraMatteTemporalPixel(f, x, y); });
}

/// Stage 4 into f.matteHistory.
template <class Exec> void maraPreBilateralStage(const Exec& e, const MaraFrame& f) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraPreBilateralPixel(f, x, y); }, 2);
}

/// Without stage 4: the temporal result is the history.
template <class Exec> void maraKeepTemporalStage(const Exec& e, const MaraFrame& f) {
    const float* from = f.temporal;
    float* to = f.matteHistory;
    e.forEachIndex(
        3 * long(f.width) * f.height, BMFR_LAMBDA(long i) { to[i] = from[i]; });
}

/// Stage 5 into f.radius.
template <class Exec> void maraDisocclusionStage(const Exec& e, const MaraFrame& f) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraRowMinPixel(f, x, y); });
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraColumnMinPixel(f, x, y); });
}

/// Stage 6 into f.median.
template <class Exec> void maraMedianStage(const Exec& e, const MaraFrame& f) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraMedianPixel(f, x, y); });
}

/// Stage 7 of `src` into f.matteOut.
template <class Exec>
void maraMatteBilateralStage(const Exec& e, const MaraFrame& f, const float* src) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraFinalBilateralPixel(f, src, x, y); }, 2);
}

/// Stage 8 into f.glossyTemporal and f.glossyHistory.
template <class Exec> void maraGlossyTemporalStage(const Exec& e, const MaraFrame& f) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) { maraGlossyTemporalPixel(f, x, y); });
}

/// Stages 9 and 10 from f.glossyTemporal into f.glossyOut.
template <class Exec> void maraGlossyBilateralStage(const Exec& e, const MaraFrame& f) {
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) {
            maraGlossyPassPixel(f, f.glossyTemporal, f.glossyRow, x, y, 1, 0);
        });
    e.forEachPixel(
        f.width, f.height, BMFR_LAMBDA(int x, int y) {
            maraGlossyPassPixel(f, f.glossyRow, f.glossyOut, x, y, 0, 1);
        });
}

/// The composition into f.composed.
template <class Exec> void maraComposeStage(const Exec& e, const MaraFrame& f) {
    e.forEachIndex(
        long(f.width) * f.height, BMFR_LAMBDA(long i) { maraComposePixel(f, i); });
}

} // namespace bmfr
