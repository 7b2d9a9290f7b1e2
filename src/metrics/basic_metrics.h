// Error metrics used by the CLI and the tests. Colour space: unless named "Linear", a metric
// compares images after the paper's display transform clamp(x^(1/2.2), 0, 1), as the BMFR paper
// scores tone-mapped output.
#pragma once
#include "core/image.h"

namespace bmfr {

/// RMSE over all pixels and channels of tone-mapped images; in [0, 1].
double rmseToneMapped(const ImageF& a, const ImageF& reference);
/// RMSE of linear radiance.
double rmseLinear(const ImageF& a, const ImageF& reference);
/// Relative MSE of linear radiance: mean((a-r)^2 / (r^2 + 0.01)).
double relMseLinear(const ImageF& a, const ImageF& reference);
/// PSNR in dB of images whose values lie in [0, range]: 10 log10(range^2 / MSE).
double psnr(const ImageF& a, const ImageF& reference, double range = 1.0);
/// PSNR in dB of tone-mapped images (peak 1).
double psnrToneMapped(const ImageF& a, const ImageF& reference);
/// Temporal error (Schied et al. 2017): mean |Y(current) - Y(previous)| of tone-mapped luminance.
double temporalError(const ImageF& current, const ImageF& previous);
/// Error of the frame-to-frame change: mean |dY(result) - dY(reference)| of tone-mapped
/// luminance, d = this frame minus the previous one. Under motion the plain temporal error also
/// counts the image's true change, so a blurred result scores lower; this one counts only the
/// change the reference does not make (flicker, lag, ghosting). It needs a converged reference,
/// as the reference's own noise adds to it.
double temporalChangeError(const ImageF& current, const ImageF& previous, const ImageF& reference,
                           const ImageF& previousReference);

} // namespace bmfr
