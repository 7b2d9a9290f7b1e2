// Per-frame line plots of one metric, laid out once as a Figure and drawn two ways: inline SVG
// for the report and papers, and an 8-bit raster for PNG. Our own small writer rather than
// matplotlib: `bmfr eval` stays one C++ program with no Python at run time, and the SVG is
// byte-for-byte deterministic.
#pragma once
#include "eval/frame_scores.h"
#include "eval/raster.h"
#include <string>
#include <vector>

namespace bmfr {

struct Series {
    std::string name;
    std::vector<double> values; ///< one per frame; NaN values are skipped (a gap in the line)
};

/// Axis ticks at "nice" values (1, 2 or 5 times a power of ten, or powers of ten on a log axis).
struct Ticks {
    double lo = 0, hi = 1;      ///< the axis range, the outermost ticks
    std::vector<double> values; ///< from lo to hi
    std::vector<std::string> labels;
};

/// Linear ticks covering [lo, hi] with about `target` intervals; zeroBased pins lo at 0 (metrics
/// that cannot be negative). A single value gets a small range around it.
Ticks niceTicks(double lo, double hi, int target = 5, bool zeroBased = false);
/// Decade ticks covering [lo, hi], lo > 0, with 2 and 5 between when the range is under two
/// decades.
Ticks logTicks(double lo, double hi);
/// Whether a log axis reads better: all values positive and spanning more than `ratio` (10: the
/// noisy input beside denoised results).
bool wantsLogAxis(const std::vector<Series>& series, double ratio = 10);

struct PlotSpec {
    std::string title;
    std::string xLabel = "frame";
    int firstFrame = 0;     ///< x = firstFrame + index
    bool zeroBased = false; ///< the y axis starts at 0 (linear axes only)
    bool logY = false;
    int width = 560, height = 330; ///< pixels (SVG user units)
};

/// Drawing primitives in pixel coordinates, y down.
struct Figure {
    struct Line {
        double x0, y0, x1, y1;
        Rgb8 colour;
        double width;
        int dash; ///< 0 solid, else a dash pattern index
    };
    struct Path {
        std::vector<std::pair<double, double>> points; ///< one unbroken polyline
        Rgb8 colour;
        double width;
        int dash;
    };
    struct Text {
        double x, y; ///< baseline
        std::string text;
        int size;   ///< pixels
        int anchor; ///< -1 start, 0 middle, 1 end
        Rgb8 colour;
    };
    int width = 0, height = 0;
    std::vector<Line> lines;
    std::vector<Path> paths;
    std::vector<Text> texts;
};

/// A metric's plot: its axis and title, and the series as drawn.
struct MetricPlot {
    PlotSpec spec;
    std::vector<Series> series;
};
/// How the report plots metric `m` per frame. SSIM is drawn as 1 - SSIM on a log axis (unless
/// `logPlots` is "off"): good denoisers' SSIM all lie within a few hundredths of 1, one band on a
/// linear axis, while their distances from 1 differ by factors, which a log axis separates. The
/// other non-negative metrics get a log axis per `logPlots`: "on", or "auto" where the values
/// span more than 10x (wantsLogAxis). The title says which way is better, and for the temporal
/// error that the reference's value is the target.
MetricPlot metricPlot(const MetricInfo& m, std::vector<Series> series, const std::string& logPlots,
                      int firstFrame);

/// The plot's layout: axes, ticks, grid, one line per series (colour and dash distinct), a full
/// legend to the right.
Figure linePlot(const PlotSpec& spec, const std::vector<Series>& series);
/// Writes `stem`.svg and `stem`.png (the PNG at twice the size).
void writePlot(const std::string& stem, const Figure& f);
/// SVG document (no XML prolog, so it can be inlined in HTML as well as saved as .svg).
std::string toSvg(const Figure& f);
/// The same figure drawn at `scale` times its size (lines and text scaled).
Raster toRaster(const Figure& f, int scale = 2);

} // namespace bmfr
