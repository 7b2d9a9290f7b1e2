#include "eval/plot.h"
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bmfr {

Raster linePlot(const std::string& title, const std::vector<Series>& series, int firstFrame,
                int width, int height) {
    Raster r(width, height);
    const int left = 90, right = 170, top = 40, bottom = 40;
    const int pw = width - left - right, ph = height - top - bottom;
    double lo = INFINITY, hi = -INFINITY;
    size_t n = 0;
    for (const Series& s : series) {
        n = std::max(n, s.values.size());
        for (double v : s.values)
            if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (!std::isfinite(lo)) lo = 0, hi = 1;
    if (hi - lo < 1e-12) hi = lo + 1e-3 * std::max(1.0, std::fabs(lo));
    const double margin = 0.05 * (hi - lo);
    lo -= margin, hi += margin;
    auto X = [&](double i) { return left + (n > 1 ? i / double(n - 1) : 0.5) * pw; };
    auto Y = [&](double v) { return top + (1 - (v - lo) / (hi - lo)) * ph; };
    const Rgb8 grid{225, 225, 225}, axis{60, 60, 60};
    char buf[64];
    for (int k = 0; k <= 4; ++k) {
        double v = lo + (hi - lo) * k / 4.0;
        r.line(left, Y(v), left + pw, Y(v), grid);
        std::snprintf(buf, sizeof buf, "%.4g", v);
        r.text(4, int(Y(v)) - 6, buf, axis);
    }
    const int tickStep = std::max(1, int(n) / 6);
    for (size_t i = 0; i < n; i += size_t(tickStep)) {
        r.line(X(double(i)), top + ph, X(double(i)), top + ph + 5, axis);
        std::snprintf(buf, sizeof buf, "%d", firstFrame + int(i));
        r.text(int(X(double(i))) - 6, top + ph + 10, buf, axis);
    }
    r.line(left, top, left, top + ph, axis);
    r.line(left, top + ph, left + pw, top + ph, axis);
    r.text(left, 10, title + "  (x: frame)", axis);
    for (size_t s = 0; s < series.size(); ++s) {
        const Rgb8 c = seriesColour(int(s));
        const std::vector<double>& v = series[s].values;
        for (size_t i = 1; i < v.size(); ++i)
            if (std::isfinite(v[i - 1]) && std::isfinite(v[i]))
                r.line(X(double(i - 1)), Y(v[i - 1]), X(double(i)), Y(v[i]), c, 2);
        if (v.size() == 1 && std::isfinite(v[0]))
            r.fillRect(int(X(0)) - 3, int(Y(v[0])) - 3, int(X(0)) + 3, int(Y(v[0])) + 3, c);
        const int ly = top + 10 + int(s) * 22;
        r.fillRect(left + pw + 12, ly, left + pw + 32, ly + 4, c);
        r.text(left + pw + 38, ly - 5, series[s].name, axis);
    }
    return r;
}

} // namespace bmfr
