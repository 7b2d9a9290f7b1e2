#include "eval/comparison.h"
#include "core/color.h"
#include "eval/crops.h"
#include "eval/plot.h"
#include "eval/report_html.h"
#include "eval/report_pictures.h"
#include "eval/run_metadata.h"
#include "eval/video.h"
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

std::string escapeHtml(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        case '\'':
            out += "&#39;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

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
    ImageF frame(int i) const {
        if (!dir_.empty())
            return readExr((fs::path(dir_) / fmt::format("denoised_{:04d}.exr", i)).string(), 3);
        FrameData f;
        noisy_->load(i, f);
        if (noisy_->info().colorIsDemodulated)
            for (size_t k = 0; k < f.color.pixels.size(); ++k)
                f.color.pixels[k] *= f.albedo.pixels[k];
        return f.color;
    }

  private:
    std::string name_, dir_;
    const SequenceReader* noisy_ = nullptr;
    std::unique_ptr<SequenceReader> owned_;
};

std::string fmtValue(double v) {
    return std::isfinite(v) ? fmt::format("{:.4f}", v) : "-";
}

/// Whether method i has the best mean of metric m (ties count as best).
bool isBest(const ComparisonResult& r, size_t i, const MetricInfo& m) {
    const double v = metricValue(r.means[i], m.key);
    if (!std::isfinite(v)) return false;
    for (const FrameScores& o : r.means) {
        const double w = metricValue(o, m.key);
        if (std::isfinite(w) && (m.lowerIsBetter ? w < v : w > v)) return false;
    }
    return true;
}

} // namespace

std::string markdownTable(const ComparisonResult& r) {
    std::string md = "| method |";
    for (const MetricInfo& m : metricList())
        md += fmt::format(" {} {} |", m.label, m.lowerIsBetter ? "↓" : "↑");
    md += "\n|---|";
    for (size_t k = 0; k < metricList().size(); ++k) md += "---|";
    md += "\n";
    for (size_t i = 0; i < r.names.size(); ++i) {
        std::string name;
        for (char c : r.names[i]) name += c == '|' ? std::string("\\|") : std::string(1, c);
        md += "| " + name + " |";
        for (const MetricInfo& m : metricList()) {
            const double v = metricValue(r.means[i], m.key);
            const bool best = isBest(r, i, m);
            md += best ? fmt::format(" **{}** |", fmtValue(v)) : fmt::format(" {} |", fmtValue(v));
        }
        md += "\n";
    }
    md += "| reference |";
    for (size_t k = 0; k + 1 < metricList().size(); ++k) md += " |";
    md += fmt::format(" {} |\n", fmtValue(r.referenceTemporalMean));
    return md;
}

namespace {

/// The tables: table.md, table.csv, per_frame.csv, table.json (keys of metricList()).
void writeTables(const ComparisonResult& r, const ComparisonOptions& o, std::string& json) {
    const fs::path out(o.output);
    writeFileAtomically((out / "table.md").string(), markdownTable(r));
    auto csvText = [](const std::string& s) {
        if (s.find_first_of(",\"\n") == std::string::npos) return s;
        std::string q = "\"";
        for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
        return q + "\"";
    };
    std::ostringstream csv, pf;
    csv << "method", pf << "method,frame";
    for (const MetricInfo& m : metricList()) csv << "," << m.key, pf << "," << m.key;
    csv << "\n", pf << "\n";
    for (size_t i = 0; i < r.names.size(); ++i) {
        csv << csvText(r.names[i]);
        for (const MetricInfo& m : metricList())
            csv << "," << csvNumber(metricValue(r.means[i], m.key));
        csv << "\n";
        for (size_t k = 0; k < r.perFrame[i].size(); ++k) {
            pf << csvText(r.names[i]) << "," << r.first + int(k);
            for (const MetricInfo& m : metricList())
                pf << "," << csvNumber(metricValue(r.perFrame[i][k], m.key));
            pf << "\n";
        }
    }
    // The reference's own temporal error, for scale; its other cells are empty.
    csv << "reference";
    for (const MetricInfo& m : metricList())
        csv << ","
            << (std::string(m.key) == "temporal_error" ? csvNumber(r.referenceTemporalMean) : "");
    csv << "\n";
    writeFileAtomically((out / "table.csv").string(), csv.str());
    writeFileAtomically((out / "per_frame.csv").string(), pf.str());

    auto num = [](double v) {
        return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    };
    nlohmann::json j;
    j["reference"] = o.reference;
    j["frames"] = {r.first, r.last};
    j["color_space"] = "RMSE, PSNR, SSIM, FLIP, temporal error: tone-mapped clamp(x^(1/2.2), 0, "
                       "1); relMSE: linear";
    j["reference_temporal_error"] = num(r.referenceTemporalMean);
    for (size_t i = 0; i < r.names.size(); ++i) {
        nlohmann::json mj;
        for (const MetricInfo& m : metricList()) {
            mj["mean"][m.key] = num(metricValue(r.means[i], m.key));
            nlohmann::json arr = nlohmann::json::array();
            for (const FrameScores& f : r.perFrame[i]) arr.push_back(num(metricValue(f, m.key)));
            mj["per_frame"][m.key] = arr;
        }
        j["methods"][r.names[i]] = mj;
    }
    json = j.dump(2) + "\n";
    writeFileAtomically((out / "table.json").string(), json);
}

std::string tableHtml(const ComparisonResult& r) {
    std::string html = "<table><tr><th>method</th>";
    for (const MetricInfo& m : metricList())
        html += fmt::format("<th>{} {}</th>", m.label, m.lowerIsBetter ? "&darr;" : "&uarr;");
    html += "</tr>";
    for (size_t i = 0; i < r.names.size(); ++i) {
        html += "<tr><td>" + escapeHtml(r.names[i]) + "</td>";
        for (const MetricInfo& m : metricList()) {
            const std::string v = fmtValue(metricValue(r.means[i], m.key));
            html += isBest(r, i, m) ? "<td><b>" + v + "</b></td>" : "<td>" + v + "</td>";
        }
        html += "</tr>";
    }
    html += "<tr><td>reference</td>";
    for (const MetricInfo& m : metricList())
        html += "<td>" +
                (std::string(m.key) == "temporal_error" ? fmtValue(r.referenceTemporalMean) : "") +
                "</td>";
    return html + "</tr></table>";
}

/// Per-pixel error of a method at the shown frame: summed absolute tone-mapped difference.
ImageF absoluteError(const ImageF& img, const ImageF& ref) {
    ImageF err(ref.width, ref.height, 1);
    for (long p = 0; p < err.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c)
            err.pixels[size_t(p)] += std::fabs(gammaEncode(img.pixels[3 * size_t(p) + size_t(c)]) -
                                               gammaEncode(ref.pixels[3 * size_t(p) + size_t(c)]));
    return err;
}

/// A file-name-safe form of a method name.
std::string fileStem(const std::string& name, size_t index) {
    std::string s = fmt::format("{}_", index);
    for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
    return s;
}

/// Everything the viewer shows, gathered frame by frame.
struct ViewerFrames {
    int factor = 1, every = 1, width = 0, height = 0;
    int shown = 0; ///< the frame the viewer opens on (the report's pictures' frame)
    std::vector<int> frames;
    std::vector<std::vector<std::string>> images, flips, files; ///< [method][frame]
    std::string json(const std::vector<std::string>& methods, int fullW, int fullH) const {
        nlohmann::json j;
        j["width"] = width, j["height"] = height, j["fullWidth"] = fullW, j["fullHeight"] = fullH;
        j["frames"] = frames;
        j["every"] = every;
        j["shown"] = shown;
        j["factor"] = factor;
        j["methods"] = methods;
        j["images"] = images;
        nlohmann::json fl = nlohmann::json::array();
        for (const auto& perMethod : flips) {
            nlohmann::json a = nlohmann::json::array();
            for (const std::string& f : perMethod)
                a.push_back(f.empty() ? nlohmann::json(nullptr) : nlohmann::json(f));
            fl.push_back(a);
        }
        j["flip"] = fl;
        j["full"] = files;
        j["magma"] = heatStops();
        // Inside <script>, "</script" or "<!--" would end or confuse the element: write every
        // '<', '>' and '&' as a JSON \u escape.
        std::string text;
        for (char c : j.dump())
            text += c == '<'   ? std::string("\\u003c")
                    : c == '>' ? std::string("\\u003e")
                    : c == '&' ? std::string("\\u0026")
                               : std::string(1, c);
        return text;
    }
};

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
    const fs::path out(o.output);
    fs::create_directories(out / "viewer");

    // The viewer embeds frames at most viewerWidth wide, and about 12 M pixels in all (a FLIP
    // map counts half): first every k-th frame (at least 8 frames, the shown one always), then
    // smaller frames. Every frame is written full size beside the report.
    ViewerFrames viewer;
    viewer.shown = show;
    const int frameCount = r.last - r.first;
    const double budget = 12e6,
                 columns = double(sources.size() + 1) + (o.flip ? 0.5 * double(sources.size()) : 0);
    viewer.factor = std::max(1, int(std::ceil(double(fullW) / std::max(16, o.viewerWidth))));
    auto pixels = [&](int factor, int every) {
        return double(fullW / factor) * double(fullH / factor) * columns *
               double((frameCount + every - 1) / every + 1);
    };
    while (pixels(viewer.factor, viewer.every) > budget &&
           (frameCount + viewer.every) / (viewer.every + 1) >= 8)
        ++viewer.every;
    while (pixels(viewer.factor, viewer.every) > budget && viewer.factor < 64) ++viewer.factor;
    viewer.width = std::max(1, fullW / viewer.factor),
    viewer.height = std::max(1, fullH / viewer.factor);
    viewer.images.assign(sources.size() + 1, {});
    viewer.flips.assign(sources.size() + 1, {});
    viewer.files.assign(sources.size() + 1, {});
    std::vector<std::string> viewerNames{"reference"};
    viewerNames.insert(viewerNames.end(), r.names.begin(), r.names.end());

    // Videos: methods side by side, and their frame-to-frame differences.
    std::string ffmpeg, videoNote;
    std::unique_ptr<VideoWriter> sideBySide, flicker;
    int videoFactor = 1;
    if (o.video) {
        ffmpeg = findFfmpeg();
        if (ffmpeg.empty()) {
            videoNote = "No video: --video needs ffmpeg on PATH (Debian: apt-get install ffmpeg).";
        } else {
            sideBySide =
                std::make_unique<VideoWriter>(ffmpeg, (out / "methods.mp4").string(), o.videoFps);
            flicker =
                std::make_unique<VideoWriter>(ffmpeg, (out / "flicker.mp4").string(), o.videoFps);
            // At most 1920 pixels wide in all.
            const int videoColumns = int(sources.size()) + 1;
            while (videoColumns * (fullW / videoFactor + 8) > 1920 && videoFactor < 16)
                ++videoFactor;
        }
    }

    r.perFrame.assign(sources.size(), {});
    std::vector<ImageF> previous(sources.size()), shown(sources.size()), shownFlip(sources.size());
    ImageF previousRef, shownRef;
    for (int i = r.first; i < r.last; ++i) {
        FrameData f;
        reference->load(i, f);
        r.referenceTemporal.push_back(i > r.first ? temporalError(f.reference, previousRef) : NAN);
        const bool embed = (i - r.first) % viewer.every == 0 || i == show;
        if (embed) viewer.frames.push_back(i);
        std::vector<ImageF> images;
        auto addViewerImage = [&](size_t column, const ImageF& img, const ImageF* flipMap) {
            const Raster full = rasterFromLinear(img);
            const std::string file =
                fmt::format("viewer/{}_{:04d}.png", fileStem(viewerNames[column], column), i);
            writePng((out / file).string(), full);
            if (!embed) return;
            viewer.files[column].push_back(file);
            viewer.images[column].push_back("data:image/png;base64," +
                                            base64(encodePng(downscale(full, viewer.factor))));
            viewer.flips[column].push_back(
                flipMap ? "data:image/png;base64," +
                              base64(encodePngGrey(downscale(greyRaster(*flipMap), viewer.factor)))
                        : std::string());
        };
        addViewerImage(0, f.reference, nullptr);
        for (size_t m = 0; m < sources.size(); ++m) {
            ImageF img = sources[m]->frame(i);
            if (img.width != f.reference.width || img.height != f.reference.height)
                throw Error(fmt::format(
                    "eval: method '{}' frame {} is {}x{}, the reference is {}x{}", r.names[m], i,
                    img.width, img.height, f.reference.width, f.reference.height));
            ImageF map;
            r.perFrame[m].push_back(scoreFrame(img, f.reference,
                                               i > r.first ? &previous[m] : nullptr, o.flip,
                                               o.flip ? &map : nullptr));
            addViewerImage(m + 1, img, o.flip ? &map : nullptr);
            if (i == show) shown[m] = img, shownFlip[m] = map;
            images.push_back(std::move(img));
        }
        if (sideBySide) {
            std::vector<const ImageF*> row{&f.reference};
            std::vector<std::string> labels{"reference"};
            std::vector<ImageF> diffs;
            for (size_t m = 0; m < images.size(); ++m) {
                row.push_back(&images[m]), labels.push_back(r.names[m]);
                ImageF d(fullW, fullH, 3);
                if (i > r.first)
                    for (size_t k = 0; k < d.pixels.size(); ++k) {
                        // x4 so that flicker shows; stored linear, so undo the display encoding.
                        const float e = 4.0f * std::fabs(gammaEncode(images[m].pixels[k]) -
                                                         gammaEncode(previous[m].pixels[k]));
                        d.pixels[k] = std::pow(std::min(e, 1.0f), 2.2f);
                    }
                diffs.push_back(std::move(d));
            }
            sideBySide->add(downscale(labelledRow(row, labels), videoFactor));
            std::vector<const ImageF*> drow;
            std::vector<std::string> dlabels;
            for (size_t m = 0; m < diffs.size(); ++m)
                drow.push_back(&diffs[m]), dlabels.push_back(r.names[m] + " |dt| x4");
            flicker->add(downscale(labelledRow(drow, dlabels), videoFactor));
        }
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
    writeTables(r, o, r.scoresJson);

    ReportContent report;
    report.heading = fmt::format("Reference: {}; frames {}:{}; pictures and heat maps of frame {}.",
                                 escapeHtml(o.reference), r.first, r.last, show);
    report.tableHtml = tableHtml(r);

    // Plots: SVG inline and beside the report, PNG beside it.
    for (const MetricInfo& m : metricList()) {
        if (std::string(m.key) == "flip" && !o.flip) continue;
        std::vector<Series> series;
        for (size_t i = 0; i < r.names.size(); ++i) {
            Series line{r.names[i], {}};
            for (const FrameScores& f : r.perFrame[i]) line.values.push_back(metricValue(f, m.key));
            series.push_back(line);
        }
        if (std::string(m.key) == "temporal_error")
            series.push_back({"reference", r.referenceTemporal});
        PlotSpec spec;
        spec.firstFrame = r.first;
        spec.zeroBased = m.nonNegative;
        spec.logY = o.logPlots == "on"
                        ? m.nonNegative
                        : o.logPlots == "auto" && m.nonNegative && wantsLogAxis(series);
        spec.title =
            fmt::format("{} ({} is better{})", m.label, m.lowerIsBetter ? "lower" : "higher",
                        spec.logY ? ", log scale" : "");
        const Figure fig = linePlot(spec, series);
        const std::string stem = fmt::format("plot_{}", m.key);
        writePlot((out / stem).string(), fig);
        report.plots.push_back({toSvg(fig), stem});
    }

    // Pictures of the shown frame.
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
        writePng((out / file).string(), img);
        report.pictures.push_back({title, base64(encodePng(img)), file, tile});
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
    report.viewerJson = viewer.json(viewerNames, fullW, fullH);

    RunMetadata meta = collectRunMetadata(o.commandLine, o.programVersion, o.reference, [&] {
        std::vector<std::pair<std::string, std::string>> m;
        for (const MethodSource& x : o.methods) m.emplace_back(x.name, x.path);
        return m;
    }());
    meta.width = fullW, meta.height = fullH, meta.firstFrame = r.first, meta.lastFrame = r.last;
    report.metadataHtml = metadataHtml(meta);
    writeFileAtomically((out / "run.json").string(), metadataJson(meta) + "\n");

    if (sideBySide) {
        sideBySide->finish();
        flicker->finish();
        r.videos = {(out / "methods.mp4").string(), (out / "flicker.mp4").string()};
        report.videos = {"methods.mp4", "flicker.mp4"};
        videoNote =
            fmt::format("methods.mp4: reference and methods side by side; flicker.mp4: each "
                        "method's absolute frame-to-frame change (tone-mapped, x4); {} fps.",
                        o.videoFps);
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
