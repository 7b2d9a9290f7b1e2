// The CPU backend's eight-wide Mara 2017 stages over rows: the sparse bilaterals (each pixel
// its own taps, gathered), the firefly median and the glossy passes (eight neighbouring pixels
// per tap). They give the reference stages' bits: the same operations in the same order, no
// fused multiply-adds.
#pragma once
#include "filters/mara2017/mara_stages.h"
#include <vector>

namespace bmfr::cpu {

/// Stage 6 on rows [y0, y1) into f.median.
void maraMedianRows(const MaraFrame& f, long y0, long y1);

/// Floats per pixel of the sparse stages' tap records: position, normal and the filtered
/// colour, four floats each (the fourth 0), one 64-byte cache line with the padding.
inline constexpr int kMaraTapRecord = 16;

/// The tap records of rows [y0, y1): f.position, f.normal (with `guide`; without, they are
/// already there) and src into `taps` (kMaraTapRecord floats per pixel, 64-byte aligned for one
/// line a tap).
void maraPackTaps(const MaraFrame& f, const float* src, bool guide, float* taps, long y0, long y1);

/// Stage 7's taps for the radii most pixels share: (1 - h) R where the history is confident,
/// R beside a disocclusion, and both boosted. Per rotation, the whole-pixel offsets and
/// Gaussian weights, as the stage computes them.
struct MaraTapTables {
    static constexpr int kRadii = 4;
    float radius[kRadii] = {};
    std::vector<int> offsets[kRadii]; ///< rotations x taps x 2
    std::vector<float> gauss[kRadii]; ///< rotations x taps
    void build(const MaraFrame& f);
};

/// Stage 4 (`final` false: into f.matteHistory) or stage 7 (`final` true: into f.matteOut) of
/// the colour packed in `taps` on the pixels [x0, x1) x [y0, y1) (x0 a multiple of 8), eight at
/// a time, each with its own taps; stage 7 looks its taps up in `tables` (may be null) where a
/// pixel's radius is one of theirs.
void maraSparseTile(const MaraFrame& f, const float* taps, bool final, int x0, int x1, long y0,
                    long y1, const MaraTapTables* tables = nullptr);

/// One glossy pass (stage 9 with (dx, dy) = (1, 0), stage 10 with (0, 1)) of src into dst on
/// rows [y0, y1). Eight pixels sharing one roughness run together; the others one by one.
void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, int dx,
                    int dy);

} // namespace bmfr::cpu
