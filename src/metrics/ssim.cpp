#include "metrics/ssim.h"
#include "core/color.h"
#include "metrics/separable_filter.h"
#include <bmfr/error.h>
#include <cmath>
#include <vector>

namespace bmfr {

namespace {

constexpr int kRadius = 5; // int(3.5 * 1.5 + 0.5)

std::vector<double> gaussianKernel() {
    std::vector<double> k(2 * kRadius + 1);
    double sum = 0;
    for (int i = -kRadius; i <= kRadius; ++i)
        sum += k[size_t(i + kRadius)] = std::exp(-0.5 * i * i / (1.5 * 1.5));
    for (double& v : k) v /= sum;
    return k;
}

std::vector<double> blur(const std::vector<double>& in, int w, int h) {
    static const std::vector<double> k = gaussianKernel();
    return separableFilter(in, w, h, k, k);
}

} // namespace

ImageF ssimMap(const ImageF& a, const ImageF& b, double range) {
    if (a.width != b.width || a.height != b.height || a.channels != b.channels || a.width == 0)
        throw Error("SSIM: images differ in size or channels");
    const int w = a.width, h = a.height, ch = a.channels;
    const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
    ImageF map(w, h, 1);
    const size_t n = size_t(w) * h;
    for (int c = 0; c < ch; ++c) {
        std::vector<double> x(n), y(n), xx(n), yy(n), xy(n);
        for (size_t i = 0; i < n; ++i) {
            x[i] = a.pixels[i * size_t(ch) + size_t(c)];
            y[i] = b.pixels[i * size_t(ch) + size_t(c)];
            xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
        }
        std::vector<double> mx = blur(x, w, h), my = blur(y, w, h), sxx = blur(xx, w, h),
                            syy = blur(yy, w, h), sxy = blur(xy, w, h);
        for (size_t i = 0; i < n; ++i) {
            double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i],
                   cxy = sxy[i] - mx[i] * my[i];
            double s = ((2 * mx[i] * my[i] + c1) * (2 * cxy + c2)) /
                       ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
            map.pixels[i] += float(s / ch);
        }
    }
    return map;
}

double ssim(const ImageF& a, const ImageF& b, double range) {
    ImageF map = ssimMap(a, b, range);
    const int w = map.width, h = map.height;
    // scikit-image averages the interior only; tiny images fall back to every pixel.
    const int pad = (w > 2 * kRadius && h > 2 * kRadius) ? kRadius : 0;
    double s = 0;
    long n = 0;
    for (int y = pad; y < h - pad; ++y)
        for (int x = pad; x < w - pad; ++x) s += map.at(x, y), ++n;
    return s / double(n);
}

ImageF toneMapped(const ImageF& linear) {
    ImageF out = linear;
    for (float& v : out.pixels) v = gammaEncode(v);
    return out;
}

} // namespace bmfr
