#include "metrics/separable_filter.h"
#include "core/border.h"
#include <algorithm>
#include <tbb/parallel_for.h>

namespace bmfr {

std::vector<double> separableFilter(const std::vector<double>& in, int w, int h,
                                    const std::vector<double>& kx, const std::vector<double>& ky,
                                    FilterBorder border) {
    auto edge = [border](int i, int n) {
        return border == FilterBorder::Clamp ? std::clamp(i, 0, n - 1) : mirrorIndex(i, n);
    };
    std::vector<double> tmp(in.size()), out(in.size(), 0.0);
    const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
    // Horizontal: only the border taps pay for the border rule.
    tbb::parallel_for(0, h, [&](int y) {
        const double* src = in.data() + size_t(y) * w;
        double* dst = tmp.data() + size_t(y) * w;
        for (int x = 0; x < w; ++x) {
            double s = 0;
            if (x >= rx && x + rx < w) {
                const double* p = src + x - rx;
                for (size_t t = 0; t < kx.size(); ++t) s += kx[t] * p[t];
            } else {
                for (int t = -rx; t <= rx; ++t) s += kx[size_t(t + rx)] * src[edge(x + t, w)];
            }
            dst[x] = s;
        }
    });
    // Vertical: whole rows at a time, so the inner loop runs along contiguous memory.
    tbb::parallel_for(0, h, [&](int y) {
        double* dst = out.data() + size_t(y) * w;
        for (int t = -ry; t <= ry; ++t) {
            const double k = ky[size_t(t + ry)];
            const double* src = tmp.data() + size_t(edge(y + t, h)) * w;
            for (int x = 0; x < w; ++x) dst[x] += k * src[x];
        }
    });
    return out;
}

} // namespace bmfr
