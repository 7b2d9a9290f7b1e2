// The CPU backend's Mara 2017 glossy passes (stages 9 and 10), eight pixels at a time, with the
// reference's bits. The edge weight is symmetric, bit for bit (maraEdgeWeight(c, q) =
// maraEdgeWeight(q, c)), so each pair of pixels k apart along the pass is weighed once and
// serves both: pixel x's tap at +k and pixel x + k's tap at -k. The passes read positions,
// normals and colours from planar copies of the rows they span, each row deinterleaved once into
// the worker's scratch, so that a tap is a plain load per channel.
#pragma once
#include "filters/mara2017/mara_stages.h"
#include <cstddef>

namespace bmfr::cpu {

/// The farthest tap the eight-wide passes take (farther reaches go pixel by pixel).
inline constexpr int kMaraGlossyMaxReach = 63;

/// The farthest tap of any pixel of the frame, capped at kMaraGlossyMaxReach: from its largest
/// roughness (a non-finite one, or none, counts as 1).
int maraGlossyReach(const MaraFrame& f);

/// The farthest tap any frame can have with these sigma settings, capped as above.
int maraGlossyReachBound(float scale, float exponent, float epsilon, float tapSigmas);

/// Floats of scratch one worker needs for a pass over rows of `width` with taps to `reach`.
size_t maraGlossyScratch(int width, int reach);

/// One glossy pass (stage 9 along the rows, or with `down` stage 10 down the columns) of src
/// into dst on rows [y0, y1), taps to `reach` (maraGlossyReach) weighed in `scratch`. Eight
/// or sixteen pixels sharing one roughness run together; the others one by one.
void maraGlossyRows(const MaraFrame& f, const float* src, float* dst, long y0, long y1, bool down,
                    int reach, float* scratch);

} // namespace bmfr::cpu
