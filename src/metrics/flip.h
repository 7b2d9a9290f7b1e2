// LDR FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images"):
// perceived difference of two sRGB-encoded images in [0, 1], per pixel in [0, 1].
// Implemented from the paper (67 pixels per degree, qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5,
// w = 0.082 degrees); every filter is separable, so a 720p frame takes a fraction of a second.
#pragma once
#include "core/image.h"

namespace bmfr {

/// Per-pixel FLIP error map (1 channel) of `test` against `reference`, both 3-channel sRGB
/// values in [0, 1] (e.g. toneMapped() output).
ImageF flipMap(const ImageF& reference, const ImageF& test, double pixelsPerDegree = 67.0);
/// Mean of flipMap.
double flip(const ImageF& reference, const ImageF& test, double pixelsPerDegree = 67.0);

} // namespace bmfr
