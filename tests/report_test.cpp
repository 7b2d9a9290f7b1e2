// The comparison report's pieces: tick choice, inset choice, escaping, the CSV/JSON schema, the
// SVG plots and the videos.
#include "cli_runner.h"
#include "eval/crops.h"
#include "eval/frame_scores.h"
#include "eval/plot.h"
#include "test_support.h"
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
    EXPECT_EQ(header(slurp(out / "table.csv")), "method" + keys);
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
