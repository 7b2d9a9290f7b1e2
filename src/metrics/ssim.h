// SSIM (Wang et al. 2004) as scikit-image computes it: 11x11 Gaussian window (sigma 1.5,
// truncated at 3.5 sigma), K1 = 0.01, K2 = 0.03, population covariances, reflect padding,
// the mean over the interior (border of 5 pixels dropped) and over channels.
#pragma once
#include "core/image.h"

namespace bmfr {

/// SSIM of two images whose values lie in [0, dataRange]; any channel count.
double ssim(const ImageF& a, const ImageF& b, double dataRange = 1.0);
/// Per-pixel SSIM map (mean over channels), same size as the inputs.
ImageF ssimMap(const ImageF& a, const ImageF& b, double dataRange = 1.0);
/// The paper's display transform applied per value: clamp(x^(1/2.2), 0, 1).
ImageF toneMapped(const ImageF& linear);

} // namespace bmfr
