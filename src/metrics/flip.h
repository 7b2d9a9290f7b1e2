// LDR FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images"):
// perceived difference of two sRGB-encoded images in [0, 1], per pixel in [0, 1].
// Written from the paper and checked against NVIDIA's implementation (github.com/NVlabs/flip,
// FLIP.h): its colour matrices, clamp-to-edge borders and default 67.02 pixels per degree (0.7 m
// from a 0.7 m wide 3840-pixel monitor); qc = 0.7, pc = 0.4, pt = 0.95, qf = 0.5, w = 0.082
// degrees. Every filter is separable, so a 720p frame takes a fraction of a second.
#pragma once
#include "core/image.h"

namespace bmfr {

/// NVIDIA's default: 0.7 m * (3840 px / 0.7 m) * pi / 180.
constexpr double kFlipDefaultPpd = 0.7 * (3840.0 / 0.7) * 3.14159265358979323846 / 180.0;

/// Per-pixel FLIP error map (1 channel) of `test` against `reference`, both 3-channel sRGB
/// values in [0, 1] (e.g. toneMapped() output).
ImageF flipMap(const ImageF& reference, const ImageF& test,
               double pixelsPerDegree = kFlipDefaultPpd);
/// Mean of a flipMap.
double flipMean(const ImageF& map);
/// Mean of flipMap.
double flip(const ImageF& reference, const ImageF& test, double pixelsPerDegree = kFlipDefaultPpd);

} // namespace bmfr
