#include "eval/comparison.h"
#include "core/color.h"
#include "eval/comparison_videos.h"
#include "eval/crops.h"
#include "eval/plot.h"
#include "eval/report_html.h"
#include "eval/report_pictures.h"
#include "eval/run_metadata.h"
#include "eval/score_tables.h"
#include "eval/viewer_frames.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/range_parsers.h"
#include "io/sequence.h"
#include "metrics/basic_metrics.h"
#include "metrics/flip.h"
#include "metrics/ssim.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cstdio>
#include <filesystem>
#include <fmt/core.h>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

/// Where a method's frames come from.
class ResultSource {
  public:
    ResultSource(const MethodSource& m, const SequenceReader& referenceReader) : name_(m.name) {
        if (m.path.empty()) {
            noisy_ = &referenceReader;
        } else if (fs::exists(fs::path(m.path) / "denoised_0000.exr") ||
                   fs::exists(fs::path(m.path) / "report.json")) {
            dir_ = m.path;
        } else {
            owned_ = SequenceReader::open(m.path);
            noisy_ = owned_.get();
        }
    }
    /// Reads the headers of frames [first, last) (sizes against the reference's): throws one
    /// bmfr::Error listing every frame that cannot be scored.
    void checkFrames(int first, int last, int width, int height) const {
        auto checkSize = [&](int w, int h, const std::string& what) {
            if (w != width || h != height)
                throw Error(
                    fmt::format("{} is {}x{}, the reference is {}x{}", what, w, h, width, height));
        };
        if (owned_) {
            owned_->checkFrames(first, last);
            checkSize(owned_->info().width, owned_->info().height, "eval: method '" + name_ + "'");
        } else if (!dir_.empty()) {
            checkEveryFrame(first, last, "eval: method '" + name_ + "'", [&](int i) {
                const ImageF img = readExr(denoised(i), 3, "", ExrContent::Header);
                checkSize(img.width, img.height, denoised(i));
            });
        }
    }
    ImageF frame(int i) const {
        if (!dir_.empty()) return readExr(denoised(i), 3);
        FrameData f;
        noisy_->load(i, f);
        if (noisy_->info().colorIsDemodulated)
            for (size_t k = 0; k < f.color.pixels.size(); ++k)
                f.color.pixels[k] *= f.albedo.pixels[k];
        return f.color;
    }

  private:
    std::string denoised(int i) const {
        return (fs::path(dir_) / fmt::format("denoised_{:04d}.exr", i)).string();
    }
    std::string name_, dir_;
    const SequenceReader* noisy_ = nullptr;
    std::unique_ptr<SequenceReader> owned_;
};

/// Per-pixel error of a method at the shown frame: summed absolute tone-mapped difference.
ImageF absoluteError(const ImageF& img, const ImageF& ref) {
    ImageF err(ref.width, ref.height, 1);
    for (long p = 0; p < err.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c)
            err.pixels[size_t(p)] += std::fabs(gammaEncode(img.pixels[3 * size_t(p) + size_t(c)]) -
                                               gammaEncode(ref.pixels[3 * size_t(p) + size_t(c)]));
    return err;
}

/// Per-metric plots: SVG inline and beside the report, PNG beside it.
std::vector<ReportPlot> writePlots(const ComparisonResult& r, const ComparisonOptions& o) {
    std::vector<ReportPlot> plots;
    for (const MetricInfo& m : metricList()) {
        if (std::string(m.key) == "flip" && !o.flip) continue;
        std::vector<Series> series;
        for (size_t i = 0; i < r.names.size(); ++i) {
            Series line{r.names[i], {}};
            for (const FrameScores& f : r.perFrame[i]) line.values.push_back(metricValue(f, m.key));
            series.push_back(line);
        }
        if (m.referenceIsTarget) series.push_back({"reference", r.referenceTemporal});
        const MetricPlot plot = metricPlot(m, std::move(series), o.logPlots, r.first);
        const Figure fig = linePlot(plot.spec, plot.series);
        const std::string stem = fmt::format("plot_{}", m.key);
        writePlot((fs::path(o.output) / stem).string(), fig);
        plots.push_back({toSvg(fig), stem});
    }

    return plots;
}

/// The shown frame side by side, its insets and its FLIP heat maps.
std::vector<ReportPicture> writePictures(ComparisonResult& r, const ComparisonOptions& o, int show,
                                         const ImageF& shownRef, const std::vector<ImageF>& shown,
                                         const std::vector<ImageF>& shownFlip) {
    std::vector<ReportPicture> pictures;
    std::vector<const ImageF*> row{&shownRef};
    std::vector<std::string> labels{"reference"};
    for (size_t m = 0; m < shown.size(); ++m)
        row.push_back(&shown[m]), labels.push_back(r.names[m]);
    std::vector<std::array<int, 4>> crops = o.crops;
    if (crops.empty()) {
        std::vector<ImageF> errors;
        for (size_t m = 0; m < shown.size(); ++m)
            if (r.names[m] != "noisy" || shown.size() == 1)
                errors.push_back(absoluteError(shown[m], shownRef));
        crops = chooseCrops(errors, o.autoCrops, o.cropSize);
    }
    r.crops = crops;
    auto addPicture = [&](const std::string& title, const std::string& file, const Raster& img,
                          bool tile = false) {
        writePng((fs::path(o.output) / file).string(), img);
        pictures.push_back({title, base64(encodePng(img)), file, tile});
    };
    std::string names;
    for (const std::string& l : labels) names += (names.empty() ? "" : ", ") + l;
    addPicture(fmt::format("Frame {}, left to right: {}", show, names), "frames.png",
               labelledRow(row, labels));
    for (size_t k = 0; k < crops.size(); ++k) {
        const auto& c = crops[k];
        addPicture(fmt::format("Inset {} at ({}, {}), {}x{} pixels, zoom {}{}", k, c[0], c[1], c[2],
                               c[3], o.zoom,
                               o.crops.empty() ? ", where the methods differ most" : ""),
                   fmt::format("crop_{}.png", k), labelledRow(row, labels, c, o.zoom));
    }
    if (o.flip) {
        std::vector<const ImageF*> maps;
        for (size_t m = 0; m < shown.size(); ++m)
            if (r.names[m] != "noisy" || shown.size() == 1) maps.push_back(&shownFlip[m]);
        const float vmax = heatScale(maps);
        for (size_t m = 0; m < shown.size(); ++m)
            addPicture(
                fmt::format("FLIP error of {} against the reference, frame {} (colour bar 0 "
                            "to {:g}; the scale is shared by all maps)",
                            r.names[m], show, vmax),
                fmt::format("heatmap_{}.png", m),
                heatMapWithBar(shownFlip[m], vmax, "FLIP, 0 to " + fmt::format("{:g}", vmax)),
                true);
    }
    return pictures;
}

} // namespace

ComparisonResult runComparison(const ComparisonOptions& o,
                               const std::function<void(int, int)>& progress) {
    if (o.methods.empty()) throw Error("eval: give at least one --method NAME=PATH");
    if (o.logPlots != "auto" && o.logPlots != "on" && o.logPlots != "off")
        throw Error("eval: --log-plots must be auto, on or off, got '" + o.logPlots + "'");
    auto reference = SequenceReader::open(o.reference);
    reference->setLayerOverrides(o.referenceLayers);
    if (!reference->info().hasReference)
        throw Error(o.reference + ": the sequence has no reference frames");
    std::vector<std::unique_ptr<ResultSource>> sources;
    ComparisonResult r;
    for (const MethodSource& m : o.methods) {
        sources.push_back(std::make_unique<ResultSource>(m, *reference));
        r.names.push_back(m.name);
    }
    std::tie(r.first, r.last) = parseFrameRange(o.frames, reference->info().frameCount);
    const int show = o.showFrame >= 0 ? o.showFrame : r.last - 1;
    if (show < r.first || show >= r.last)
        throw Error(fmt::format("eval: frame {} is outside {}:{}", show, r.first, r.last));
    const int fullW = reference->info().width, fullH = reference->info().height;
    for (const auto& c : o.crops)
        if (c[2] <= 0 || c[3] <= 0 || c[0] < 0 || c[1] < 0 || c[0] >= fullW || c[1] >= fullH ||
            c[2] > fullW - c[0] || c[3] > fullH - c[1])
            throw Error(fmt::format("eval: crop {},{},{},{} is outside the {}x{} frame", c[0], c[1],
                                    c[2], c[3], fullW, fullH));
    // Every frame's headers before the first output: a bad frame fails the run here.
    reference->checkFrames(r.first, r.last);
    for (const auto& s : sources) s->checkFrames(r.first, r.last, fullW, fullH);
    const fs::path out(o.output);

    std::vector<std::string> columns{"reference"};
    columns.insert(columns.end(), r.names.begin(), r.names.end());
    ViewerFrames viewer(columns, fullW, fullH, r.first, r.last, show, o.flip, o.viewerWidth,
                        o.output, o.videoFps);

    // Videos, when asked for and ffmpeg is there.
    const std::string ffmpeg = o.video ? findFfmpeg() : std::string();
    std::unique_ptr<ComparisonVideos> videos;
    if (!ffmpeg.empty())
        videos = std::make_unique<ComparisonVideos>(ffmpeg, o.output, o.videoFps, r.names, fullW);

    r.perFrame.assign(sources.size(), {});
    std::vector<ImageF> previous(sources.size()), shown(sources.size()), shownFlip(sources.size());
    ImageF previousRef, shownRef;
    for (int i = r.first; i < r.last; ++i) {
        FrameData f;
        reference->load(i, f);
        r.referenceTemporal.push_back(i > r.first ? temporalError(f.reference, previousRef) : NAN);
        std::vector<ImageF> images;
        viewer.add(0, i, f.reference, nullptr);
        for (size_t m = 0; m < sources.size(); ++m) {
            ImageF img = sources[m]->frame(i);
            if (img.width != f.reference.width || img.height != f.reference.height)
                throw Error(fmt::format(
                    "eval: method '{}' frame {} is {}x{}, the reference is {}x{}", r.names[m], i,
                    img.width, img.height, f.reference.width, f.reference.height));
            ImageF map;
            const PreviousScoredFrame before{previous[m], previousRef};
            r.perFrame[m].push_back(scoreFrame(img, f.reference, i > r.first ? &before : nullptr,
                                               o.flip, o.flip ? &map : nullptr));
            viewer.add(m + 1, i, img, o.flip ? &map : nullptr);
            if (i == show) shown[m] = img, shownFlip[m] = map;
            images.push_back(std::move(img));
        }
        if (videos) videos->add(f.reference, images, previous);
        for (size_t m = 0; m < images.size(); ++m) previous[m] = std::move(images[m]);
        if (i == show) shownRef = f.reference;
        previousRef = std::move(f.reference);
        progress(i - r.first + 1, r.last - r.first);
    }
    for (const auto& frames : r.perFrame) r.means.push_back(meanScores(frames));
    double s = 0;
    int n = 0;
    for (double v : r.referenceTemporal)
        if (std::isfinite(v)) s += v, ++n;
    r.referenceTemporalMean = n ? s / n : NAN;
    RunMetadata meta = collectRunMetadata(o.commandLine, o.programVersion, o.reference, [&] {
        std::vector<std::pair<std::string, std::string>> m;
        for (const MethodSource& x : o.methods) m.emplace_back(x.name, x.path);
        return m;
    }());
    meta.width = fullW, meta.height = fullH, meta.firstFrame = r.first, meta.lastFrame = r.last;
    r.runs = meta.methods;
    writeTables(r, o, r.scoresJson);

    ReportContent report;
    report.heading = fmt::format("Reference: {}; frames {}:{}; pictures and heat maps of frame {}.",
                                 escapeHtml(o.reference), r.first, r.last, show);
    report.tableHtml = tableHtml(r);

    report.plots = writePlots(r, o);

    report.pictures = writePictures(r, o, show, shownRef, shown, shownFlip);
    report.viewerJson = viewer.json();

    report.metadataHtml = metadataHtml(meta);
    writeFileAtomically((out / "run.json").string(), metadataJson(meta) + "\n");

    std::string videoNote;
    if (videos) {
        r.videos = videos->finish();
        report.videos = {"methods.mp4", "flicker.mp4"};
        videoNote = fmt::format("methods.mp4: the reference and the methods side by side; "
                                "flicker.mp4: each method's absolute frame-to-frame change "
                                "(tone-mapped, x4); {} fps.",
                                o.videoFps);
    } else if (o.video) {
        videoNote = "No video: --video needs ffmpeg on PATH (Debian: apt-get install ffmpeg).";
    }
    report.videoNote = videoNote;
    r.reportPath = (out / "report.html").string();
    writeFileAtomically(r.reportPath, reportHtml(report));
    if (o.video && ffmpeg.empty())
        throw Error("eval --video: ffmpeg was not found on PATH (Debian: apt-get install ffmpeg); "
                    "the tables, plots and " +
                    r.reportPath + " were written, without videos");
    return r;
}

} // namespace bmfr
