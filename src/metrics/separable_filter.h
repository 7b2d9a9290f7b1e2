// Separable convolution, rows in parallel: the one filter routine that SSIM and FLIP share.
#pragma once
#include <vector>

namespace bmfr {

/// How taps outside the image read: Mirror (d c b a | a b c d, as scikit-image's SSIM) or
/// Clamp (a a a a | a b c d, as NVIDIA's FLIP).
enum class FilterBorder { Mirror, Clamp };

/// out = (in * kx along x) * ky along y; kernels of odd length, centred.
std::vector<double> separableFilter(const std::vector<double>& in, int width, int height,
                                    const std::vector<double>& kx, const std::vector<double>& ky,
                                    FilterBorder border = FilterBorder::Mirror);

} // namespace bmfr
