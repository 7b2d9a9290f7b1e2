// The CPU backend's vector Mara 2017 stages over rows: the sparse bilaterals and the firefly
// median (the glossy passes: cpu_mara_glossy.h). They give the reference stages' bits (the same
// operations in the same order, no fused multiply-adds), except where a run of pixels shares a
// sparse stage's rotation and radius: there the taps that land on one pixel are merged into one, so
// the sums round differently (held to the reference by the conformance suite's tolerance).
#pragma once
#include "filters/mara2017/mara_stages.h"
#include <vector>

namespace bmfr::cpu {

/// Stage 6 on rows [y0, y1) into f.median.
void maraMedianRows(const MaraFrame& f, long y0, long y1);

/// The taps a run of pixels shares when they share a rotation and a radius: per rotation,
/// each distinct whole-pixel offset once, first come first, with the Gaussian weights of the
/// taps that land on it summed (a radius of 1.28 pixels puts 50 taps on 9 pixels).
struct MaraTapRuns {
    std::vector<int> begin; ///< kMaraSpiralRotations + 1: where each rotation's taps start
    std::vector<int> dx, dy;
    std::vector<float> g;
    /// From kMaraSpiralRotations x taps offsets (x, y) and Gaussian weights.
    void build(const int* offsets, const float* gauss, int taps);
};

/// Stage 4's taps, and stage 7's for the radii most pixels share: (1 - h) R where the history
/// is confident, R beside a disocclusion, and both boosted. Per rotation, the whole-pixel
/// offsets and Gaussian weights as the stage computes them, and merged into runs.
struct MaraTapTables {
    static constexpr int kRadii = 4;
    float radius[kRadii] = {};
    std::vector<int> offsets[kRadii]; ///< rotations x taps x 2
    std::vector<float> gauss[kRadii]; ///< rotations x taps
    MaraTapRuns runs[kRadii];
    MaraTapRuns pre; ///< stage 4's, from f.preOffsets and f.preGauss
    void reserve(int taps);
    void buildPre(const MaraFrame& f);
    void buildFinal(const MaraFrame& f);
};

/// Stage 4 (`final` false: into f.matteHistory) or stage 7 (`final` true: into f.matteOut) of
/// src on the pixels [x0, x1) x [y0, y1) (x0 a multiple of 8), eight at a time, or sixteen on
/// the AVX-512 path where a run of rotationWidth (a multiple of 16) covers them. Pixels that
/// share a rotation (rotationWidth a multiple of 8) read each tap's eight or sixteen neighbours
/// as one run, for each of their radii in turn when they have one or two (the lanes of the other
/// adding 0); sixteen with more radii go as two eights, and eight with more gather each pixel's
/// own taps. Every path gives the same bits.
void maraSparseTile(const MaraFrame& f, const float* src, bool final, int x0, int x1, long y0,
                    long y1, const MaraTapTables& tables);

} // namespace bmfr::cpu
