#include "eval/crops.h"
#include <algorithm>
#include <cmath>

namespace bmfr {

namespace {

/// Summed-area table of a 1-channel map, (w + 1) x (h + 1).
std::vector<double> integral(const ImageF& m) {
    const int w = m.width, h = m.height;
    std::vector<double> s(size_t(w + 1) * size_t(h + 1), 0.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            s[size_t(y + 1) * (w + 1) + x + 1] = m.at(x, y) + s[size_t(y) * (w + 1) + x + 1] +
                                                 s[size_t(y + 1) * (w + 1) + x] -
                                                 s[size_t(y) * (w + 1) + x];
    return s;
}

} // namespace

std::vector<std::array<int, 4>> chooseCrops(const std::vector<ImageF>& errors, int count,
                                            int size) {
    std::vector<std::array<int, 4>> out;
    if (errors.empty() || count <= 0) return out;
    const int w = errors[0].width, h = errors[0].height;
    size = std::min({size, w, h});
    if (size <= 0) return out;
    std::vector<std::vector<double>> sums;
    for (const ImageF& e : errors) sums.push_back(integral(e));
    auto windowMean = [&](size_t m, int x, int y) {
        const std::vector<double>& s = sums[m];
        const size_t W = size_t(w + 1);
        return (s[size_t(y + size) * W + size_t(x + size)] - s[size_t(y) * W + size_t(x + size)] -
                s[size_t(y + size) * W + size_t(x)] + s[size_t(y) * W + size_t(x)]) /
               (double(size) * size);
    };
    struct Candidate {
        double score;
        int x, y;
    };
    std::vector<Candidate> candidates;
    const int stride = std::max(1, size / 4);
    for (int y = 0; y + size <= h; y += stride)
        for (int x = 0; x + size <= w; x += stride) {
            double lo = INFINITY, hi = -INFINITY;
            for (size_t m = 0; m < errors.size(); ++m) {
                const double v = windowMean(m, x, y);
                lo = std::min(lo, v), hi = std::max(hi, v);
            }
            candidates.push_back({errors.size() > 1 ? hi - lo : hi, x, y});
        }
    // Ties broken by position, so that the choice is deterministic.
    std::stable_sort(candidates.begin(), candidates.end(),
                     [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
    const int cells = std::max(2, int(std::ceil(std::sqrt(double(count)))) + 1);
    std::vector<char> cellUsed(size_t(cells) * cells, 0);
    for (const Candidate& c : candidates) {
        if (int(out.size()) >= count) break;
        const int cx = c.x + size / 2, cy = c.y + size / 2;
        const size_t cell = size_t(std::min(cells - 1, cy * cells / h)) * cells +
                            size_t(std::min(cells - 1, cx * cells / w));
        if (cellUsed[cell]) continue;
        bool near = false;
        for (const auto& o : out) near = near || std::hypot(o[0] - c.x, o[1] - c.y) < 1.5 * size;
        if (near) continue;
        cellUsed[cell] = 1;
        out.push_back({c.x, c.y, size, size});
    }
    return out;
}

} // namespace bmfr
