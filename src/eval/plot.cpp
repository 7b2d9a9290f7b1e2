#include "eval/plot.h"
#include "eval/escape_html.h"
#include "io/atomic_file.h"
#include <algorithm>
#include <cmath>
#include <fmt/core.h>

namespace bmfr {

namespace {

/// Label for a tick value at a tick spacing of `step`: as many decimals as the step needs.
std::string tickLabel(double v, double step) {
    if (std::fabs(v) < 1e-12 * std::max(1.0, std::fabs(step))) return "0";
    const double a = std::fabs(v);
    if (a >= 1e5 || a < 1e-3) return fmt::format("{:.0e}", v);
    const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
    return fmt::format("{:.{}f}", v, decimals);
}

double niceStep(double rough) {
    const double p = std::pow(10.0, std::floor(std::log10(rough)));
    const double m = rough / p;
    return (m <= 1 ? 1 : m <= 2 ? 2 : m <= 2.5 ? 2.5 : m <= 5 ? 5 : 10) * p;
}

const char* svgDash(int dash) {
    static const char* d[] = {"", "7 4", "2 3", "9 3 2 3", "4 4", "12 4"};
    return d[dash % 6];
}

std::string hex(Rgb8 c) {
    return fmt::format("#{:02x}{:02x}{:02x}", c.r, c.g, c.b);
}

/// Approximate advance of the SVG sans-serif text, for layout.
double textWidthEstimate(const std::string& s, int size) {
    return 0.56 * size * double(s.size());
}

} // namespace

Ticks niceTicks(double lo, double hi, int target, bool zeroBased) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0, hi = 1;
    if (zeroBased) lo = std::min(0.0, lo), hi = std::max(hi, 0.0);
    if (hi - lo < 1e-12 * std::max(1.0, std::fabs(hi))) {
        const double pad = std::fabs(hi) > 0 ? 0.1 * std::fabs(hi) : 1.0;
        hi += pad;
        if (!zeroBased || lo > 0) lo -= pad;
    }
    const double step = niceStep((hi - lo) / std::max(1, target));
    Ticks t;
    t.lo = std::floor(lo / step + 1e-9) * step;
    t.hi = std::ceil(hi / step - 1e-9) * step;
    if (zeroBased && lo >= 0) t.lo = std::max(t.lo, 0.0);
    for (int k = 0;; ++k) {
        const double v = t.lo + k * step;
        if (v > t.hi + 1e-9 * step) break;
        t.values.push_back(std::fabs(v) < 1e-12 * step ? 0.0 : v);
        t.labels.push_back(tickLabel(t.values.back(), step));
    }
    return t;
}

Ticks logTicks(double lo, double hi) {
    Ticks t;
    if (!(lo > 0) || !(hi > 0)) return niceTicks(lo, hi);
    const int e0 = int(std::floor(std::log10(lo) + 1e-9)),
              e1 = int(std::ceil(std::log10(hi) - 1e-9));
    const int decades = std::max(1, e1 - e0);
    t.lo = std::pow(10.0, e0), t.hi = std::pow(10.0, std::max(e1, e0 + 1));
    for (int e = e0; e <= e0 + decades; ++e)
        for (double m : decades < 2 ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
            const double v = m * std::pow(10.0, e);
            if (v > t.hi * (1 + 1e-9)) break;
            t.values.push_back(v);
            t.labels.push_back(tickLabel(v, v));
        }
    return t;
}

bool wantsLogAxis(const std::vector<Series>& series, double ratio) {
    double lo = INFINITY, hi = 0;
    for (const Series& s : series)
        for (double v : s.values) {
            if (!std::isfinite(v)) continue;
            if (v <= 0) return false;
            lo = std::min(lo, v), hi = std::max(hi, v);
        }
    return hi > 0 && hi / lo > ratio;
}

MetricPlot metricPlot(const MetricInfo& m, std::vector<Series> series, const std::string& logPlots,
                      int firstFrame) {
    MetricPlot p{{}, std::move(series)};
    p.spec.firstFrame = firstFrame;
    p.spec.zeroBased = m.nonNegative;
    if (std::string(m.key) == "ssim") {
        for (Series& s : p.series)
            for (double& v : s.values) v = 1 - v;
        p.spec.zeroBased = true;
        p.spec.logY = logPlots != "off";
        p.spec.title =
            p.spec.logY ? "1 - SSIM (log), lower is better" : "1 - SSIM, lower is better";
        return p;
    }
    p.spec.logY =
        m.nonNegative && (logPlots == "on" || (logPlots == "auto" && wantsLogAxis(p.series)));
    const std::string better = m.referenceIsTarget ? "the reference's is the target"
                               : m.lowerIsBetter   ? "lower is better"
                                                   : "higher is better";
    p.spec.title = fmt::format("{} ({}{})", m.label, better, p.spec.logY ? ", log scale" : "");
    return p;
}

Figure linePlot(const PlotSpec& spec, const std::vector<Series>& series) {
    Figure f;
    f.width = spec.width, f.height = spec.height;
    const Rgb8 ink{40, 40, 40}, grid{228, 228, 228}, axis{110, 110, 110};
    size_t n = 0;
    double lo = INFINITY, hi = -INFINITY;
    for (const Series& s : series) {
        n = std::max(n, s.values.size());
        for (double v : s.values)
            if (std::isfinite(v) && (!spec.logY || v > 0))
                lo = std::min(lo, v), hi = std::max(hi, v);
    }
    if (!std::isfinite(lo)) lo = spec.logY ? 0.1 : 0, hi = 1; // nothing to draw: an empty axis
    const Ticks yt = spec.logY ? logTicks(lo, hi) : niceTicks(lo, hi, 5, spec.zeroBased);
    // Legend width from the longest name, so that no name is clipped.
    double legendW = 0;
    for (const Series& s : series) legendW = std::max(legendW, textWidthEstimate(s.name, 12));
    legendW += 44;
    double labelW = 0;
    for (const std::string& l : yt.labels) labelW = std::max(labelW, textWidthEstimate(l, 12));
    const double left = labelW + 18, top = 34, bottom = 42;
    f.width = std::max(spec.width, int(left + 220 + legendW));
    const double pw = f.width - left - legendW - 12, ph = spec.height - top - bottom;
    const double x0 = left, y0 = top + ph;
    auto X = [&](double i) { return x0 + (n > 1 ? i / double(n - 1) : 0.5) * pw; };
    auto Y = [&](double v) {
        const double t = spec.logY ? (std::log10(v) - std::log10(yt.lo)) /
                                         (std::log10(yt.hi) - std::log10(yt.lo))
                                   : (v - yt.lo) / (yt.hi - yt.lo);
        return y0 - t * ph;
    };
    f.texts.push_back({x0, 20, spec.title, 14, -1, ink});
    for (size_t k = 0; k < yt.values.size(); ++k) {
        const double y = Y(yt.values[k]);
        f.lines.push_back({x0, y, x0 + pw, y, grid, 1, 0});
        f.texts.push_back({x0 - 6, y + 4, yt.labels[k], 12, 1, ink});
    }
    // Frame ticks: a nice integer step.
    const Ticks xt =
        niceTicks(spec.firstFrame, spec.firstFrame + double(std::max<size_t>(n, 1) - 1), 6);
    const double xstep = std::max(1.0, xt.values.size() > 1 ? xt.values[1] - xt.values[0] : 1.0);
    for (double v = std::ceil(spec.firstFrame / xstep) * xstep;
         v <= spec.firstFrame + double(n) - 1 + 1e-9; v += xstep) {
        const double x = X(v - spec.firstFrame);
        f.lines.push_back({x, y0, x, y0 + 5, axis, 1, 0});
        f.texts.push_back({x, y0 + 19, fmt::format("{}", int(std::lround(v))), 12, 0, ink});
    }
    f.texts.push_back({x0 + pw / 2, y0 + 36, spec.xLabel, 12, 0, ink});
    f.lines.push_back({x0, top, x0, y0, axis, 1, 0});
    f.lines.push_back({x0, y0, x0 + pw, y0, axis, 1, 0});
    for (size_t s = 0; s < series.size(); ++s) {
        const Rgb8 c = seriesColour(int(s));
        const int dash = int(s / 8); // colours repeat after eight; dashes then tell them apart
        Figure::Path path{{}, c, 2, dash};
        const std::vector<double>& v = series[s].values;
        for (size_t i = 0; i <= v.size(); ++i) {
            const bool ok = i < v.size() && std::isfinite(v[i]) && (!spec.logY || v[i] > 0);
            if (ok) path.points.push_back({X(double(i)), Y(v[i])});
            if (!ok && !path.points.empty()) {
                if (path.points.size() == 1) // a lone point: a short tick so that it shows
                    path.points.push_back({path.points[0].first + 0.01, path.points[0].second});
                f.paths.push_back(path);
                path.points.clear();
            }
        }
        const double ly = top + 8 + double(s) * 20, lx = x0 + pw + 14;
        f.lines.push_back({lx, ly, lx + 24, ly, c, 2.5, dash});
        f.texts.push_back({lx + 30, ly + 4, series[s].name, 12, -1, ink});
    }
    return f;
}

std::string toSvg(const Figure& f) {
    std::string s = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 "
        "{0} {1}\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">"
        "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>",
        f.width, f.height);
    auto dash = [](int d) {
        return d ? fmt::format(" stroke-dasharray=\"{}\"", svgDash(d)) : std::string();
    };
    for (const Figure::Line& l : f.lines)
        s += fmt::format("<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" "
                         "stroke=\"{}\" stroke-width=\"{}\"{}/>",
                         l.x0, l.y0, l.x1, l.y1, hex(l.colour), l.width, dash(l.dash));
    for (const Figure::Path& p : f.paths) {
        std::string pts;
        for (const auto& [x, y] : p.points) pts += fmt::format("{:.1f},{:.1f} ", x, y);
        s += fmt::format("<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" "
                         "stroke-linejoin=\"round\"{} points=\"{}\"/>",
                         hex(p.colour), p.width, dash(p.dash), pts);
    }
    for (const Figure::Text& t : f.texts)
        s += fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" font-size=\"{}\" fill=\"{}\"{}>{}</text>",
                         t.x, t.y, t.size, hex(t.colour),
                         t.anchor < 0   ? ""
                         : t.anchor > 0 ? " text-anchor=\"end\""
                                        : " text-anchor=\"middle\"",
                         escapeHtml(t.text));
    return s + "</svg>";
}

void writePlot(const std::string& stem, const Figure& f) {
    writeFileAtomically(stem + ".svg",
                        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + toSvg(f) + "\n");
    writePng(stem + ".png", toRaster(f, 2));
}

Raster toRaster(const Figure& f, int scale) {
    Raster r(f.width * scale, f.height * scale);
    auto segment = [&](double x0, double y0, double x1, double y1, Rgb8 c, double w, int dash) {
        const int thick = std::max(1, int(std::lround(w * scale)));
        if (!dash) return r.line(x0 * scale, y0 * scale, x1 * scale, y1 * scale, c, thick);
        const double len = std::hypot(x1 - x0, y1 - y0), on = 6, off = 4;
        for (double a = 0; a < len; a += on + off) {
            const double b = std::min(len, a + on);
            r.line((x0 + (x1 - x0) * a / len) * scale, (y0 + (y1 - y0) * a / len) * scale,
                   (x0 + (x1 - x0) * b / len) * scale, (y0 + (y1 - y0) * b / len) * scale, c,
                   thick);
        }
    };
    for (const Figure::Line& l : f.lines)
        segment(l.x0, l.y0, l.x1, l.y1, l.colour, l.width, l.dash);
    for (const Figure::Path& p : f.paths)
        for (size_t i = 1; i < p.points.size(); ++i)
            segment(p.points[i - 1].first, p.points[i - 1].second, p.points[i].first,
                    p.points[i].second, p.colour, p.width, p.dash);
    for (const Figure::Text& t : f.texts) {
        const int fs = std::max(1, int(std::lround(t.size * scale / 8.0)));
        const int w = textWidth(t.text, fs);
        const int x = int(t.x * scale) - (t.anchor < 0 ? 0 : t.anchor > 0 ? w : w / 2);
        r.text(x, int(t.y * scale) - 7 * fs, t.text, t.colour, fs);
    }
    return r;
}

} // namespace bmfr
