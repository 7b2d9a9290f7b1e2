// Separable convolution with reflect padding (d c b a | a b c d), rows in parallel: the one
// filter routine that SSIM and FLIP share.
#pragma once
#include <vector>

namespace bmfr {

/// out = (in * kx along x) * ky along y; kernels of odd length, centred.
std::vector<double> separableFilter(const std::vector<double>& in, int width, int height,
                                    const std::vector<double>& kx, const std::vector<double>& ky);

} // namespace bmfr
