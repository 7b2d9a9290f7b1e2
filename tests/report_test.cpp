// The comparison report's pieces: tick choice, inset choice, escaping, the CSV/JSON schema, the
// score tables' bold values and notes, the SVG plots, the viewer's opening error scales and
// frame rate, and the videos.
#include "cli_runner.h"
#include "eval/crops.h"
#include "eval/frame_scores.h"
#include "eval/plot.h"
#include "eval/score_tables.h"
#include "eval/viewer_frames.h"
#include "test_support.h"
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>

namespace bmfr {
namespace {

namespace fs = std::filesystem;
using testing::runCli;

bool isNice(double step) {
    const double m = step / std::pow(10.0, std::floor(std::log10(step) + 1e-12));
    for (double n : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (std::fabs(m - n) < 1e-9) return true;
    return false;
}

TEST(ReportTicks, NiceValuesCoverTheRange) {
    for (auto [lo, hi] : {std::pair{0.0123, 0.08255},
                          {20.9, 34.5},
                          {0.36, 0.89},
                          {-3.0, 7.0},
                          {1.0, 1.0},
                          {1e-4, 3e-4},
                          {0.0, 0.0}}) {
        const Ticks t = niceTicks(lo, hi, 5);
        ASSERT_GE(t.values.size(), 2u) << lo << " " << hi;
        EXPECT_LE(t.lo, lo);
        EXPECT_GE(t.hi, hi);
        const double step = t.values[1] - t.values[0];
        EXPECT_TRUE(isNice(step)) << step;
        EXPECT_LE(t.values.size(), 12u);
        for (size_t k = 1; k < t.values.size(); ++k)
            EXPECT_NEAR(t.values[k] - t.values[k - 1], step, 1e-9 * step);
        EXPECT_EQ(t.labels.size(), t.values.size());
    }
    // Labels are short and exact: no "0.08255"-style raw numbers.
    const Ticks t = niceTicks(0.0123, 0.08255, 5);
    for (const std::string& l : t.labels) EXPECT_LE(l.size(), 4u) << l;
    EXPECT_EQ(t.labels.back(), "0.10");
}

TEST(ReportTicks, NonNegativeMetricsStartAtZero) {
    const Ticks t = niceTicks(0.0188, 0.0901, 5, true);
    EXPECT_EQ(t.lo, 0.0);
    EXPECT_EQ(t.labels.front(), "0");
    EXPECT_GE(t.hi, 0.0901);
    // Never below zero, even for a constant series.
    const Ticks c = niceTicks(0.5, 0.5, 5, true);
    EXPECT_EQ(c.lo, 0.0);
    EXPECT_GE(c.hi, 0.5);
    // Without the flag the axis hugs the data.
    EXPECT_GT(niceTicks(20.9, 34.5, 5).lo, 0.0);
}

TEST(ReportTicks, LogAxisForWideRanges) {
    const Ticks t = logTicks(0.0042, 0.101);
    EXPECT_NEAR(t.lo, 0.001, 1e-15);
    EXPECT_NEAR(t.hi, 1.0, 1e-12);
    EXPECT_EQ(t.labels.front(), "0.001");
    const Ticks narrow = logTicks(0.02, 0.09); // under two decades: 1, 2, 5 steps
    EXPECT_GE(narrow.values.size(), 4u);
    EXPECT_TRUE(wantsLogAxis({{"noisy", {0.1, 0.11}}, {"bmfr", {0.004, 0.005}}}));
    EXPECT_FALSE(wantsLogAxis({{"a", {0.1, 0.2}}, {"b", {0.05, 0.06}}}));
    EXPECT_FALSE(wantsLogAxis({{"a", {0.0, 0.2}}, {"b", {0.001, 0.06}}})) << "a zero";
}

TEST(ReportPlots, SvgHasEveryNameInFullAndOneLinePerSeries) {
    PlotSpec spec;
    spec.title = "RMSE <lower> & better";
    spec.zeroBased = true;
    const std::vector<Series> series = {{"accumulation", {0.1, 0.09, NAN, 0.08}},
                                        {"bmfr without TAA", {0.02, 0.019, 0.018, 0.017}},
                                        {"bmfr without fitting", {0.05, 0.04, 0.045, 0.041}}};
    const Figure f = linePlot(spec, series);
    const std::string svg = toSvg(f);
    for (const Series& s : series) EXPECT_NE(svg.find(">" + s.name + "<"), std::string::npos);
    EXPECT_NE(svg.find("RMSE &lt;lower&gt; &amp; better"), std::string::npos);
    // The NaN splits the first series in two.
    size_t lines = 0;
    for (size_t at = svg.find("<polyline"); at != std::string::npos;
         at = svg.find("<polyline", at + 1))
        ++lines;
    EXPECT_EQ(lines, 4u);
    // The legend fits: every text starts inside the figure, and the longest name's estimated
    // end too.
    for (const Figure::Text& t : f.texts) {
        EXPECT_GE(t.x, 0);
        EXPECT_LT(t.x + (t.anchor < 0 ? 0.56 * t.size * double(t.text.size()) : 0), f.width + 1)
            << t.text;
    }
    const Raster png = toRaster(f, 2);
    EXPECT_EQ(png.width, 2 * f.width);
    size_t dark = 0;
    for (const Rgb8& p : png.pixels) dark += p.r < 128 && p.g < 128 && p.b < 128;
    EXPECT_GT(dark, 500u) << "text and axes are drawn";
}

const MetricInfo& metricNamed(const std::string& key) {
    for (const MetricInfo& m : metricList())
        if (m.key == key) return m;
    throw std::runtime_error("no metric " + key);
}

TEST(ReportPlots, SsimIsPlottedAsOneMinusSsimOnALogAxis) {
    // SSIM 0.99 and 0.999 are 1 - SSIM = 0.01 and 0.001: a decade apart on the log axis, whose
    // ticks are 0.001, 0.002, 0.005 and 0.01.
    const MetricPlot p =
        metricPlot(metricNamed("ssim"), {{"a", {0.99, 0.999}}, {"b", {0.995, NAN}}}, "auto", 5);
    ASSERT_EQ(p.series.size(), 2u);
    EXPECT_NEAR(p.series[0].values[0], 0.01, 1e-12);
    EXPECT_NEAR(p.series[0].values[1], 0.001, 1e-12);
    EXPECT_NEAR(p.series[1].values[0], 0.005, 1e-12);
    EXPECT_TRUE(std::isnan(p.series[1].values[1]));
    EXPECT_TRUE(p.spec.logY);
    EXPECT_EQ(p.spec.firstFrame, 5);
    EXPECT_NE(p.spec.title.find("1 - SSIM (log)"), std::string::npos) << p.spec.title;
    const std::string svg = toSvg(linePlot(p.spec, p.series));
    for (const char* tick : {">0.001<", ">0.002<", ">0.005<", ">0.01<"})
        EXPECT_NE(svg.find(tick), std::string::npos) << tick;
    EXPECT_NE(svg.find("1 - SSIM (log)"), std::string::npos);
    // A log axis even where the values span under 10x; --log-plots off keeps 1 - SSIM, linear.
    EXPECT_TRUE(metricPlot(metricNamed("ssim"), {{"a", {0.96, 0.97}}}, "auto", 0).spec.logY);
    const MetricPlot off = metricPlot(metricNamed("ssim"), {{"a", {0.96, 0.97}}}, "off", 0);
    EXPECT_FALSE(off.spec.logY);
    EXPECT_NEAR(off.series[0].values[0], 0.04, 1e-12);
    EXPECT_EQ(off.spec.title, "1 - SSIM, lower is better");
    // The other metrics as before: log where they span more than 10x or when asked.
    const MetricPlot rmse = metricPlot(metricNamed("rmse"), {{"a", {0.02, 0.03}}}, "auto", 0);
    EXPECT_FALSE(rmse.spec.logY);
    EXPECT_EQ(rmse.series[0].values[0], 0.02);
    EXPECT_EQ(rmse.spec.title, "RMSE (lower is better)");
    EXPECT_TRUE(metricPlot(metricNamed("rmse"), {{"a", {0.02, 0.03}}}, "on", 0).spec.logY);
    EXPECT_EQ(metricPlot(metricNamed("psnr_db"), {{"a", {30, 31}}}, "on", 0).spec.title,
              "PSNR dB (higher is better)");
    // The temporal error's target is the reference's value: its title says so, not "lower".
    EXPECT_EQ(metricPlot(metricNamed("temporal_error"), {{"a", {0.02, 0.03}}}, "off", 0).spec.title,
              "temporal error (the reference's is the target)");
}

/// A table of three methods whose means are set by hand (FLIP and relMSE missing).
ComparisonResult threeMethods(std::vector<std::string> names) {
    ComparisonResult r;
    r.names = std::move(names);
    const double v[3][5] = {// rmse, psnr, ssim, temporal, change
                            {0.05, 26, 0.90, 0.010, 0.004},
                            {0.10, 20, 0.95, 0.030, 0.006},
                            {0.08, 22, 0.92, 0.018, 0.005}};
    for (const auto& row : v) {
        FrameScores f;
        f.rmse = row[0], f.psnr = row[1], f.ssim = row[2], f.temporal = row[3];
        f.temporalChange = row[4];
        r.means.push_back(f);
        r.perFrame.push_back({f});
    }
    r.referenceTemporalMean = 0.020;
    return r;
}

TEST(ReportTables, BoldOnlyWhereLowerOrHigherIsBetterAndNoneForTemporalError) {
    // Temporal errors 0.010, 0.030 and 0.018 against the reference's 0.020: the lowest, 0.010,
    // is not the best (its target is the reference's value), and none is bold. Change error: the
    // lowest, 0.004, is best; RMSE the lowest, PSNR and SSIM the highest.
    const std::string md = markdownTable(threeMethods({"a", "b", "c"}));
    EXPECT_NE(md.find("| method | RMSE ↓ | PSNR dB ↑ | SSIM ↑ | FLIP ↓ | relMSE ↓ | temporal "
                      "error → ref | change error ↓ |\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| a | **0.0500** | **26.0000** | 0.9000 | - | - | 0.0100 | **0.0040** |\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| b | 0.1000 | 20.0000 | **0.9500** | - | - | 0.0300 | 0.0060 |\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| c | 0.0800 | 22.0000 | 0.9200 | - | - | 0.0180 | 0.0050 |\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| reference |  |  |  |  |  | 0.0200 |  |\n"), std::string::npos) << md;

    const std::string html = tableHtml(threeMethods({"a", "b", "c"}));
    EXPECT_NE(html.find("<th>temporal error &rarr; ref</th>"), std::string::npos) << html;
    EXPECT_NE(html.find("<th>change error &darr;</th>"), std::string::npos) << html;
    for (const char* v : {"0.0100", "0.0300", "0.0180"})
        EXPECT_EQ(html.find(std::string("<b>") + v), std::string::npos) << v;
    EXPECT_NE(html.find("<td><b>0.0040</b></td>"), std::string::npos) << html;
    EXPECT_NE(html.find("<td><b>0.9500</b></td>"), std::string::npos) << html;
}

TEST(ReportTables, NotesSayWhatTheDemosRowsAreAndHowTheTemporalColumnsRead) {
    // The demo's names: each gets its gloss, and the TAA trade is explained.
    const ComparisonResult demo = threeMethods({"noisy", "bmfr", "bmfr without TAA"});
    const std::string md = markdownTable(demo);
    const size_t notes = md.find("\n\n- ");
    ASSERT_NE(notes, std::string::npos) << md;
    EXPECT_EQ(md.find("- Rows: noisy = the input; bmfr = BMFR, the default (quality preset); "
                      "bmfr without TAA = bmfr, TAA off.\n"),
              notes + 2)
        << md;
    EXPECT_NE(md.find("TAA blends each frame with its reprojected history", notes),
              std::string::npos);
    EXPECT_NE(md.find("read it against the reference row's value: lower is not better (lag, "
                      "smearing); none is bold.",
                      notes),
              std::string::npos);
    EXPECT_NE(md.find("change error: mean |ΔY - ΔY of the reference|, lower is better", notes),
              std::string::npos);
    // Short there: at most four lines under the table.
    EXPECT_LE(std::count(md.begin() + long(notes) + 2, md.end(), '\n'), 4) << md;

    const std::string html = tableHtml(demo);
    const size_t end = html.find("</table>");
    for (const char* text :
         {"<i>bmfr</i>, BMFR as bmfr denoise runs it by default",
          "<i>bmfr without TAA</i>, bmfr with its final TAA turned off",
          "temporal anti-aliasing over the already-denoised output",
          "its per-frame scores (RMSE, PSNR, SSIM, FLIP, relMSE) are worse with TAA",
          "temporal stability", "lower than the reference's is not better, it means lag or",
          "Temporal error (&rarr; ref)", "Change error (&darr;)"}) {
        const size_t at = html.find(text);
        EXPECT_NE(at, std::string::npos) << text;
        EXPECT_GT(at, end) << text;
    }

    // Eval's own names: no gloss and no TAA line, only the columns' reading.
    const ComparisonResult eval = threeMethods({"mine", "theirs", "<b>x</b>"});
    const std::string plain = markdownTable(eval), evalHtml = tableHtml(eval);
    EXPECT_EQ(plain.find("Rows:"), std::string::npos) << plain;
    EXPECT_EQ(plain.find("TAA"), std::string::npos) << plain;
    EXPECT_NE(plain.find("- temporal error: mean |ΔY| from the previous frame"), std::string::npos);
    EXPECT_EQ(evalHtml.find("Rows:"), std::string::npos);
    EXPECT_EQ(evalHtml.find("<b>x</b>"), std::string::npos) << "names stay escaped";
    EXPECT_NE(evalHtml.find("Temporal error (&rarr; ref)"), std::string::npos);
    // A user's name with TAA in it brings the TAA line, but no gloss.
    const std::string ablation = markdownTable(threeMethods({"ours", "ours no taa", "x"}));
    EXPECT_EQ(ablation.find("Rows:"), std::string::npos);
    EXPECT_NE(ablation.find("TAA blends each frame"), std::string::npos);
}

TEST(ReportTables, TimeColumnFromEachRunsRecordWithItsMachineAndOidnSaysSingleFrame) {
    // No method recorded a time: no column, no note.
    EXPECT_EQ(markdownTable(threeMethods({"a", "b", "c"})).find("ms/frame"), std::string::npos);

    ComparisonResult r = threeMethods({"noisy", "fast one", "theirs"});
    r.runs.resize(3);
    r.runs[1].stageMs = {{"fit", 1.0}, {"total", 2.5}};
    r.runs[1].machine = "CPU X, 2 threads";
    r.runs[2].stageMs = {{"filter", 150.0}, {"total", 168.4}};
    r.runs[2].machine = "CPU X, 2 threads";
    r.runs[2].filter = "oidn";
    r.runs[2].description = "OIDN 2.5.1, RT filter";
    const std::string md = markdownTable(r);
    EXPECT_NE(md.find("| change error ↓ | ms/frame ↓ |\n|---|---|---|---|---|---|---|---|---|\n"),
              std::string::npos)
        << md;
    EXPECT_NE(md.find("| **0.0040** | - |\n"), std::string::npos) << "the input has no time\n"
                                                                  << md;
    EXPECT_NE(md.find("| **2.50** |\n"), std::string::npos) << "the fastest in bold\n" << md;
    EXPECT_NE(md.find("| 168 |\n"), std::string::npos) << md;
    EXPECT_NE(md.find("theirs = Intel Open Image Denoise, single-frame"), std::string::npos) << md;
    EXPECT_NE(md.find("ms/frame: the median time per frame of each method's own run (its "
                      "report.json), reading and writing files excluded, on CPU X, 2 threads.\n"),
              std::string::npos)
        << md;
    const std::string html = tableHtml(r);
    EXPECT_NE(html.find("<th>ms/frame &darr;</th>"), std::string::npos) << html;
    EXPECT_NE(html.find("<td><b>2.50</b></td>"), std::string::npos) << html;
    EXPECT_NE(html.find("Intel Open Image Denoise (OIDN 2.5.1, RT filter), the denoiser Blender "
                        "and most offline renderers ship: single-frame"),
              std::string::npos)
        << html;

    // Times from two machines: each named with its methods.
    r.runs[2].machine = "CPU Y, 16 threads";
    EXPECT_NE(markdownTable(r).find("on CPU X, 2 threads (fast one); CPU Y, 16 threads (theirs)."),
              std::string::npos)
        << markdownTable(r);
}

/// Rasters for the viewer's error scales: one colour everywhere but for `changed`, pixel i of
/// which gets colour changed[i].
Raster rasterWith(Rgb8 base, const std::vector<std::pair<int, Rgb8>>& changed) {
    Raster r(10, 10, base);
    for (auto [i, c] : changed) r.pixels[size_t(i)] = c;
    return r;
}

TEST(ReportViewer, ErrorViewsPerPixelAsTheViewerComputesThem) {
    const Raster white = rasterWith({255, 255, 255}, {});
    const Raster a =
        rasterWith({255, 255, 255}, {{0, {0, 255, 255}}, {1, {0, 0, 255}}, {2, {0, 0, 0}}});
    const std::vector<float> abs = viewerError(a, white, ViewerError::Absolute);
    ASSERT_EQ(abs.size(), 100u);
    EXPECT_NEAR(abs[0], 1.0 / 3, 1e-6);
    EXPECT_NEAR(abs[1], 2.0 / 3, 1e-6);
    EXPECT_NEAR(abs[2], 1.0, 1e-6);
    EXPECT_EQ(abs[3], 0.0f);
    // Relative: |0 - 1| / (1 + 0.01) per black channel, over three channels.
    const std::vector<float> rel = viewerError(a, white, ViewerError::Relative);
    EXPECT_NEAR(rel[0], 1 / 1.01 / 3, 1e-6);
    EXPECT_NEAR(rel[2], 1 / 1.01, 1e-6);
    // Half grey (128) against white: (1 - (128/255)^2.2) / 1.01 on every channel.
    const Raster grey = rasterWith({128, 128, 128}, {});
    EXPECT_NEAR(viewerError(grey, white, ViewerError::Relative)[0],
                (1 - std::pow(128.0 / 255, 2.2)) / 1.01, 1e-5);
    // FLIP: the grey map's level / 255; B is not used.
    EXPECT_NEAR(viewerError(grey, Raster(0, 0), ViewerError::Flip)[0], 128.0 / 255, 1e-7);
}

TEST(ReportViewer, OpeningErrorScaleIsTheBestMethodsNinetyNinthPercentile) {
    // 100 values 0.00 .. 0.99: the 99th percentile (nearest rank: the 99th smallest) is 0.98.
    std::vector<float> ramp;
    for (int i = 0; i < 100; ++i) ramp.push_back(float(i) / 100);
    std::vector<float> doubled;
    for (float v : ramp) doubled.push_back(2 * v);
    const std::vector<float> zero(100, 0.0f);
    // The best (lowest mean) of the eligible: the ramp, not the doubled ramp, and not the zero
    // map, which is not eligible (the noisy input's place).
    EXPECT_NEAR(openingErrorScale({zero, doubled, ramp}, {false, true, true}), 0.98, 1e-6);
    EXPECT_NEAR(openingErrorScale({doubled}, {true}), 1.96, 1e-6);
    // None eligible: all compete. The scale stays within the slider, [0.001, 10].
    EXPECT_NEAR(openingErrorScale({zero, ramp}, {false, false}), 0.001, 1e-12);
    EXPECT_NEAR(openingErrorScale({std::vector<float>(100, 50.0f)}, {true}), 10.0, 1e-12);
    EXPECT_NEAR(openingErrorScale({ramp}, {true}, 0.5), 0.49, 1e-6);
}

TEST(ReportViewer, JsonCarriesTheOpeningErrorScalesAndTheFrameRate) {
    // A white reference; "good" darkens 5 pixels in one channel, 4 in two and 1 in all three
    // (abs errors 1/3, 2/3, 1: the 99th smallest of 100 is 2/3); "worse" blackens 10 pixels;
    // "noisy" is exact and left out. FLIP maps: good's pixel i is i/100, stored as the level
    // round(255 i / 100): the 99th smallest is 250/255; worse's is 1 everywhere.
    const int w = 10, h = 10;
    const fs::path dir = testing::freshDir("report", "viewer");
    ViewerFrames v({"reference", "noisy", "worse", "good"}, w, h, 0, 1, 0, true, 640, dir.string(),
                   30);
    auto image = [&](auto darkChannels) {
        ImageF img(w, h, 3);
        for (int p = 0; p < w * h; ++p)
            for (int c = 0; c < 3; ++c) img.pixels[size_t(3 * p + c)] = c < darkChannels(p) ? 0 : 1;
        return img;
    };
    const ImageF white = image([](int) { return 0; });
    const ImageF good = image([](int p) { return p >= 99 ? 3 : p >= 95 ? 2 : p >= 90 ? 1 : 0; });
    const ImageF worse = image([](int p) { return p >= 90 ? 3 : 0; });
    ImageF zeroMap(w, h, 1), oneMap(w, h, 1), rampMap(w, h, 1);
    for (int p = 0; p < w * h; ++p)
        oneMap.pixels[size_t(p)] = 1, rampMap.pixels[size_t(p)] = p / 100.0f;
    v.add(0, 0, white, nullptr);
    v.add(1, 0, white, &zeroMap);
    v.add(2, 0, worse, &oneMap);
    v.add(3, 0, good, &rampMap);
    const auto j = nlohmann::json::parse(v.json());
    ASSERT_TRUE(j.contains("errorScale")) << j.dump().substr(0, 200);
    EXPECT_NEAR(j["errorScale"]["abs"].get<double>(), 2.0 / 3, 1e-6);
    EXPECT_NEAR(j["errorScale"]["rel"].get<double>(), 2.0 / 3 / 1.01, 1e-6);
    EXPECT_NEAR(j["errorScale"]["flip"].get<double>(), 250.0 / 255, 1e-6);
    EXPECT_EQ(j["fps"], 30);
}

ImageF spots(int w, int h, std::vector<std::array<int, 3>> centres) {
    ImageF m(w, h, 1);
    for (auto [cx, cy, strength] : centres)
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                m.at(x, y) += float(strength) *
                              std::exp(-float((x - cx) * (x - cx) + (y - cy) * (y - cy)) / 50.0f);
    return m;
}

TEST(ReportCrops, InsetsGoWhereMethodsDifferFromDistinctRegions) {
    // Both methods err strongly at the top left (where they agree); they differ at three places,
    // two of them close together at the bottom right.
    const ImageF a =
        spots(192, 128, {{{20, 20, 10}}, {{170, 110, 4}}, {{150, 100, 4}}, {{90, 20, 3}}});
    const ImageF b = spots(192, 128, {{{20, 20, 10}}});
    const auto crops = chooseCrops({a, b}, 3, 24);
    ASSERT_EQ(crops.size(), 3u);
    auto centreNear = [&](const std::array<int, 4>& c, int x, int y) {
        return std::hypot(c[0] + c[2] / 2 - x, c[1] + c[3] / 2 - y) < 16;
    };
    EXPECT_TRUE(centreNear(crops[0], 170, 110) || centreNear(crops[0], 150, 100));
    bool top = false, agreeing = false;
    for (const auto& c : crops) {
        top = top || centreNear(c, 90, 20);
        agreeing = agreeing || centreNear(c, 20, 20);
        for (const auto& d : crops)
            if (&c != &d) {
                EXPECT_GE(std::hypot(c[0] - d[0], c[1] - d[1]), 1.5 * 24);
            }
    }
    EXPECT_TRUE(top) << "the third inset is the distinct region";
    EXPECT_FALSE(agreeing) << "where the methods agree is not shown";
    // One method: its own largest error.
    const auto single = chooseCrops({b}, 1, 24);
    ASSERT_EQ(single.size(), 1u);
    EXPECT_TRUE(centreNear(single[0], 20, 20));
}

using testing::slurp;

TEST(ReportOutputs, NamesAreEscapedAndTablesShareOneNumericSchema) {
    const fs::path in = testing::scratchPath("report", "in"),
                   den = testing::scratchPath("report", "den"),
                   out = testing::scratchPath("report", "out");
    ASSERT_EQ(runCli("synth -o " + in.string() + " --width 48 --height 32 --frames 3 -q").code, 0);
    ASSERT_EQ(runCli("denoise " + in.string() + " -o " + den.string() + " -q --no-png").code, 0);
    const std::string evil = "<script>alert(1)</script>\\\"x, y";
    const auto e = runCli("eval -r " + in.string() + " -m noisy -m \"" + evil + "=" + den.string() +
                          "\" -o " + out.string() + " -q");
    ASSERT_EQ(e.code, 0) << e.output;
    const std::string html = slurp(out / "report.html");
    EXPECT_EQ(html.find("<script>alert"), std::string::npos);
    EXPECT_NE(html.find("&lt;script&gt;alert(1)&lt;/script&gt;"), std::string::npos);
    // In the viewer's JSON, "</" cannot end its <script> element.
    const size_t data = html.find("id=\"viewer-data\">");
    ASSERT_NE(data, std::string::npos);
    const size_t from = data + 17, to = html.find("</script>", data);
    const auto viewer = nlohmann::json::parse(html.substr(from, to - from));
    EXPECT_EQ(viewer["methods"][2], "<script>alert(1)</script>\"x, y");

    // One schema: denoise's scores.csv and eval's per_frame.csv carry the same metric keys;
    // every cell is a number or empty.
    auto header = [](const std::string& csv) { return csv.substr(0, csv.find('\n')); };
    const std::string scores = slurp(den / "scores.csv"), perFrame = slurp(out / "per_frame.csv");
    std::string keys;
    for (const MetricInfo& m : metricList()) keys += std::string(",") + m.key;
    EXPECT_EQ(header(scores).rfind("frame" + keys, 0), 0u) << header(scores);
    EXPECT_EQ(header(perFrame), "method,frame" + keys);
    EXPECT_EQ(header(slurp(out / "table.csv")), "method" + keys + ",ms_per_frame");
    std::istringstream rows(scores);
    std::string row;
    std::getline(rows, row);
    int cells = 0;
    while (std::getline(rows, row)) {
        std::stringstream cellsIn(row);
        std::string cell;
        while (std::getline(cellsIn, cell, ',')) {
            ++cells;
            if (cell.empty()) continue;
            size_t used = 0;
            EXPECT_NO_THROW((void)std::stod(cell, &used)) << cell;
            EXPECT_EQ(used, cell.size()) << cell;
        }
    }
    EXPECT_GT(cells, 20);
    const auto den_json = nlohmann::json::parse(slurp(den / "report.json"));
    const auto eval_json = nlohmann::json::parse(slurp(out / "table.json"));
    for (const MetricInfo& m : metricList()) {
        EXPECT_TRUE(den_json["scores"].contains(m.key)) << m.key;
        EXPECT_TRUE(eval_json["methods"]["noisy"]["mean"].contains(m.key)) << m.key;
    }
    // The first frame's temporal error is missing: empty in CSV, null in JSON.
    EXPECT_TRUE(eval_json["methods"]["noisy"]["per_frame"]["temporal_error"][0].is_null());
    // Times per frame as the denoise run recorded them, with its machine; none for the input.
    EXPECT_TRUE(eval_json["methods"]["noisy"]["ms_per_frame"].is_null());
    const auto& denoised = eval_json["methods"][viewer["methods"][2].get<std::string>()];
    EXPECT_EQ(denoised["ms_per_frame"].get<double>(), den_json["median_ms"]["total"].get<double>());
    EXPECT_EQ(denoised["machine"], den_json["machine"]);
    EXPECT_NE(den_json["machine"].get<std::string>().find(" threads"), std::string::npos);
    // The report holds the notes under its table, SSIM as 1 - SSIM on a log axis, a play button
    // and the viewer's frame rate (--video-fps, 24 by default) and opening error scales.
    const size_t notes = html.find("<p class=\"notes\">");
    EXPECT_NE(notes, std::string::npos);
    EXPECT_GT(notes, html.find("</table>"));
    EXPECT_NE(slurp(out / "plot_ssim.svg").find("1 - SSIM (log)"), std::string::npos);
    EXPECT_NE(html.find("<button id=\"v-play\">"), std::string::npos);
    EXPECT_EQ(viewer["fps"], 24);
    for (const char* view : {"abs", "rel", "flip"}) {
        EXPECT_GE(viewer["errorScale"][view].get<double>(), 0.001) << view;
        EXPECT_LE(viewer["errorScale"][view].get<double>(), 10.0) << view;
    }
    for (const fs::path& p : {in, den, out}) fs::remove_all(p);
}

TEST(ReportOutputs, VideosNeedFfmpegAndTheReportIsWrittenWithout) {
    const fs::path in = testing::scratchPath("report", "vin"),
                   den = testing::scratchPath("report", "vden"),
                   out = testing::scratchPath("report", "vout"),
                   noFfmpeg = testing::scratchPath("report", "vnone");
    ASSERT_EQ(runCli("synth -o " + in.string() + " --width 48 --height 32 --frames 4 -q").code, 0);
    ASSERT_EQ(runCli("denoise " + in.string() + " -o " + den.string() + " -q --no-png").code, 0);
    const std::string args = "eval -r " + in.string() + " -m noisy -m bmfr=" + den.string() +
                             " -q --no-flip --video -o ";
    // Without ffmpeg on PATH: a clear error, exit 1, and the rest of the report.
    const std::string cmd = std::string("env PATH=/nonexistent ") + BMFR_CLI_PATH + " " + args +
                            noFfmpeg.string() + " 2>&1";
    FILE* p = popen(cmd.c_str(), "r");
    std::string text;
    char buf[512];
    while (fgets(buf, sizeof buf, p)) text += buf;
    const int status = pclose(p);
    EXPECT_EQ(WEXITSTATUS(status), 1) << text;
    EXPECT_NE(text.find("ffmpeg was not found on PATH"), std::string::npos) << text;
    EXPECT_TRUE(fs::exists(noFfmpeg / "report.html"));
    EXPECT_TRUE(fs::exists(noFfmpeg / "table.csv"));
    EXPECT_FALSE(fs::exists(noFfmpeg / "methods.mp4"));
    EXPECT_NE(slurp(noFfmpeg / "report.html").find("No video: --video needs ffmpeg"),
              std::string::npos);

    // With ffmpeg (scripts/install-deps.sh --tests installs it): H.264 MP4s, one frame each.
    const auto ok = runCli(args + out.string());
    ASSERT_EQ(ok.code, 0) << ok.output;
    for (const char* v : {"methods.mp4", "flicker.mp4"}) {
        ASSERT_TRUE(fs::exists(out / v)) << v;
        const auto probe = [&] {
            FILE* f = popen(("ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                             "stream=codec_name,nb_read_frames -of csv=p=0 " +
                             (out / v).string())
                                .c_str(),
                            "r");
            std::string s;
            while (fgets(buf, sizeof buf, f)) s += buf;
            pclose(f);
            return s;
        }();
        EXPECT_EQ(probe, "h264,4\n") << v;
    }
    for (const fs::path& q : {in, den, out, noFfmpeg}) fs::remove_all(q);
}

} // namespace
} // namespace bmfr
