#include "eval/comparison.h"
#include "core/color.h"
#include "eval/plot.h"
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

/// Top-left corners of up to `count` non-overlapping windows with the largest summed error.
std::vector<std::array<int, 4>> chooseCrops(const ImageF& error, int count, int size) {
    std::vector<std::array<int, 4>> out;
    size = std::min({size, error.width, error.height});
    const int stride = std::max(1, size / 2);
    struct Cand {
        double score;
        int x, y;
    };
    std::vector<Cand> cands;
    for (int y = 0; y + size <= error.height; y += stride)
        for (int x = 0; x + size <= error.width; x += stride) {
            double s = 0;
            for (int j = y; j < y + size; ++j)
                for (int i = x; i < x + size; ++i) s += error.at(i, j);
            cands.push_back({s, x, y});
        }
    std::sort(cands.begin(), cands.end(),
              [](const Cand& a, const Cand& b) { return a.score > b.score; });
    for (const Cand& c : cands) {
        if (int(out.size()) >= count) break;
        bool overlaps = false;
        for (const auto& o : out)
            overlaps = overlaps || (std::abs(o[0] - c.x) < size && std::abs(o[1] - c.y) < size);
        if (!overlaps) out.push_back({c.x, c.y, size, size});
    }
    return out;
}

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
        md += "| " + r.names[i] + " |";
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

ComparisonResult runComparison(const ComparisonOptions& o,
                               const std::function<void(int, int)>& progress) {
    if (o.methods.empty()) throw Error("eval: give at least one --method NAME=PATH");
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
    fs::create_directories(o.output);
    r.perFrame.assign(sources.size(), {});
    std::vector<ImageF> previous(sources.size());
    std::vector<ImageF> shown(sources.size());
    ImageF previousRef, shownRef;
    for (int i = r.first; i < r.last; ++i) {
        FrameData f;
        reference->load(i, f);
        r.referenceTemporal.push_back(i > r.first ? temporalError(f.reference, previousRef) : NAN);
        for (size_t m = 0; m < sources.size(); ++m) {
            ImageF img = sources[m]->frame(i);
            if (img.width != f.reference.width || img.height != f.reference.height)
                throw Error(fmt::format(
                    "eval: method '{}' frame {} is {}x{}, the reference is {}x{}", r.names[m], i,
                    img.width, img.height, f.reference.width, f.reference.height));
            r.perFrame[m].push_back(
                scoreFrame(img, f.reference, i > r.first ? &previous[m] : nullptr, o.flip));
            if (i == show) shown[m] = img;
            previous[m] = std::move(img);
        }
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

    // Tables.
    const std::string md = markdownTable(r);
    writeFileAtomically((fs::path(o.output) / "table.md").string(), md);
    {
        std::ostringstream csv;
        csv << "method";
        for (const MetricInfo& m : metricList()) csv << "," << m.key;
        csv << "\n";
        for (size_t i = 0; i < r.names.size(); ++i) {
            csv << r.names[i];
            for (const MetricInfo& m : metricList())
                csv << "," << fmtValue(metricValue(r.means[i], m.key));
            csv << "\n";
        }
        csv << "reference,,,,,," << fmtValue(r.referenceTemporalMean) << "\n";
        writeFileAtomically((fs::path(o.output) / "table.csv").string(), csv.str());
        std::ostringstream pf;
        pf << "method,frame";
        for (const MetricInfo& m : metricList()) pf << "," << m.key;
        pf << "\n";
        for (size_t i = 0; i < r.names.size(); ++i)
            for (size_t k = 0; k < r.perFrame[i].size(); ++k) {
                pf << r.names[i] << "," << r.first + int(k);
                for (const MetricInfo& m : metricList())
                    pf << "," << fmtValue(metricValue(r.perFrame[i][k], m.key));
                pf << "\n";
            }
        writeFileAtomically((fs::path(o.output) / "per_frame.csv").string(), pf.str());
    }
    nlohmann::json j;
    j["reference"] = o.reference;
    j["frames"] = {r.first, r.last};
    j["color_space"] = "RMSE, PSNR, SSIM, FLIP, temporal error: tone-mapped clamp(x^(1/2.2), 0, "
                       "1); relMSE: linear";
    j["reference_temporal_error"] = r.referenceTemporalMean;
    for (size_t i = 0; i < r.names.size(); ++i) {
        nlohmann::json mj;
        for (const MetricInfo& m : metricList()) {
            double v = metricValue(r.means[i], m.key);
            mj["mean"][m.key] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
            nlohmann::json arr = nlohmann::json::array();
            for (const FrameScores& f : r.perFrame[i]) {
                double x = metricValue(f, m.key);
                arr.push_back(std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr));
            }
            mj["per_frame"][m.key] = arr;
        }
        j["methods"][r.names[i]] = mj;
    }
    r.scoresJson = j.dump(2) + "\n";
    writeFileAtomically((fs::path(o.output) / "table.json").string(), r.scoresJson);

    // Plots.
    std::vector<std::pair<std::string, Raster>> plots;
    for (const MetricInfo& m : metricList()) {
        if (std::string(m.key) == "flip" && !o.flip) continue;
        std::vector<Series> series;
        for (size_t i = 0; i < r.names.size(); ++i) {
            Series line{r.names[i], {}};
            for (const FrameScores& f : r.perFrame[i]) line.values.push_back(metricValue(f, m.key));
            series.push_back(line);
        }
        if (std::string(m.key) == "temporal") series.push_back({"reference", r.referenceTemporal});
        Raster plot = linePlot(std::string(m.label) +
                                   (m.lowerIsBetter ? " (lower is better)" : " (higher is better)"),
                               series, r.first);
        writePng((fs::path(o.output) / fmt::format("plot_{}.png", m.key)).string(), plot);
        plots.emplace_back(m.label, std::move(plot));
    }

    // Pictures of the shown frame: full frames, crops, heat maps.
    std::vector<std::array<int, 4>> crops = o.crops;
    if (crops.empty()) {
        ImageF err(shownRef.width, shownRef.height, 1);
        int counted = 0;
        for (size_t m = 0; m < shown.size(); ++m) {
            if (r.names[m] == "noisy" && shown.size() > 1) continue;
            ++counted;
            for (long p = 0; p < err.pixelCount(); ++p)
                for (int c = 0; c < 3; ++c)
                    err.pixels[size_t(p)] +=
                        std::fabs(gammaEncode(shown[m].pixels[3 * size_t(p) + size_t(c)]) -
                                  gammaEncode(shownRef.pixels[3 * size_t(p) + size_t(c)]));
        }
        (void)counted;
        crops = chooseCrops(err, o.autoCrops, o.cropSize);
    }
    const int labelH = 30;
    std::vector<std::pair<std::string, Raster>> pictures;
    {
        // Reference and methods side by side at full size (scaled down for wide frames).
        const int cols = int(shown.size()) + 1, w = shownRef.width, h = shownRef.height;
        Raster all(cols * (w + 8), h + labelH);
        for (int c = 0; c < cols; ++c) {
            const ImageF& img = c == 0 ? shownRef : shown[size_t(c - 1)];
            all.blit(rasterFromLinear(img), c * (w + 8), labelH);
            all.text(c * (w + 8) + 4, 6, c == 0 ? "reference" : r.names[size_t(c - 1)], {0, 0, 0});
        }
        writePng((fs::path(o.output) / "frames.png").string(), all);
        pictures.emplace_back(fmt::format("Frame {}", show), std::move(all));
    }
    for (size_t k = 0; k < crops.size(); ++k) {
        const auto& c = crops[k];
        if (c[2] <= 0 || c[3] <= 0 || c[0] < 0 || c[1] < 0 || c[0] >= shownRef.width ||
            c[1] >= shownRef.height || c[2] > shownRef.width - c[0] ||
            c[3] > shownRef.height - c[1])
            throw Error(fmt::format("eval: crop {},{},{},{} is outside the {}x{} frame", c[0], c[1],
                                    c[2], c[3], shownRef.width, shownRef.height));
        const int cols = int(shown.size()) + 1, cw = c[2] * o.zoom, ch = c[3] * o.zoom;
        Raster row(cols * (cw + 8), ch + labelH);
        for (int i = 0; i < cols; ++i) {
            const ImageF& img = i == 0 ? shownRef : shown[size_t(i - 1)];
            row.blit(rasterFromLinear(img, c[0], c[1], c[2], c[3], o.zoom), i * (cw + 8), labelH);
            row.text(i * (cw + 8) + 4, 6, i == 0 ? "reference" : r.names[size_t(i - 1)], {0, 0, 0});
        }
        writePng((fs::path(o.output) / fmt::format("crop_{}.png", k)).string(), row);
        pictures.emplace_back(fmt::format("Crop {} at ({}, {}), {}x{} pixels, zoom {}", k, c[0],
                                          c[1], c[2], c[3], o.zoom),
                              std::move(row));
    }
    for (size_t m = 0; m < shown.size(); ++m) {
        ImageF map = flipMap(toneMapped(shownRef), toneMapped(shown[m]));
        Raster heat = heatMap(map, 1.0f);
        writePng((fs::path(o.output) / fmt::format("heatmap_{}.png", m)).string(), heat);
        pictures.emplace_back(fmt::format("FLIP error map: {} (black 0, yellow 1)", r.names[m]),
                              std::move(heat));
    }

    // The self-contained HTML report.
    std::string html =
        "<!doctype html><html><head><meta charset=\"utf-8\"><title>bmfr eval</title><style>"
        "body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse}"
        "td,th{border:1px solid #ccc;padding:4px "
        "10px;text-align:right}td:first-child{text-align:left}"
        "img{max-width:100%;image-rendering:pixelated}</style></head><body>";
    html += fmt::format("<h1>bmfr eval</h1><p>Reference: {}; frames {}:{}; shown frame {}.</p>",
                        escapeHtml(o.reference), r.first, r.last, show);
    html += "<p>RMSE, PSNR, SSIM, FLIP and temporal error are computed on tone-mapped frames, "
            "clamp(x<sup>1/2.2</sup>, 0, 1), as the BMFR paper scores; relMSE on linear radiance. "
            "Best value per column in bold.</p><table><tr><th>method</th>";
    for (const MetricInfo& m : metricList())
        html += fmt::format("<th>{} {}</th>", m.label, m.lowerIsBetter ? "&darr;" : "&uarr;");
    html += "</tr>";
    for (size_t i = 0; i < r.names.size(); ++i) {
        html += "<tr><td>" + escapeHtml(r.names[i]) + "</td>";
        for (const MetricInfo& m : metricList()) {
            const double v = metricValue(r.means[i], m.key);
            const bool best = isBest(r, i, m);
            html += best ? "<td><b>" + fmtValue(v) + "</b></td>" : "<td>" + fmtValue(v) + "</td>";
        }
        html += "</tr>";
    }
    html += fmt::format("<tr><td>reference</td>{}<td>{}</td></tr></table>",
                        std::string("<td></td><td></td><td></td><td></td><td></td>"),
                        fmtValue(r.referenceTemporalMean));
    html += "<h2>Per frame</h2>";
    for (const auto& [title, img] : plots)
        html += "<p><img alt=\"" + escapeHtml(title) + "\" src=\"data:image/png;base64," +
                base64(encodePng(img)) + "\"></p>";
    html += "<h2>Pictures</h2>";
    for (const auto& [title, img] : pictures)
        html += "<h3>" + escapeHtml(title) + "</h3><p><img src=\"data:image/png;base64," +
                base64(encodePng(img)) + "\"></p>";
    html += "</body></html>\n";
    r.reportPath = (fs::path(o.output) / "report.html").string();
    writeFileAtomically(r.reportPath, html);
    return r;
}

} // namespace bmfr
