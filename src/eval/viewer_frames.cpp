#include "eval/viewer_frames.h"
#include "eval/raster.h"
#include "eval/report_pictures.h"
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fmt/core.h>
#include <nlohmann/json.hpp>

namespace bmfr {

namespace fs = std::filesystem;

namespace {

/// A file-name-safe form of a column's name.
std::string fileStem(const std::string& name, size_t index) {
    std::string s = fmt::format("{}_", index);
    for (char c : name) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '-';
    return s;
}

std::string dataUri(const std::vector<unsigned char>& png) {
    return "data:image/png;base64," + base64(png);
}

} // namespace

std::vector<float> viewerError(const Raster& a, const Raster& b, ViewerError view) {
    static const std::array<float, 256> linear = [] {
        std::array<float, 256> l{};
        for (int v = 0; v < 256; ++v) l[size_t(v)] = std::pow(float(v) / 255.0f, 2.2f);
        return l;
    }();
    if (view != ViewerError::Flip && b.pixels.size() != a.pixels.size()) return {};
    std::vector<float> e(a.pixels.size());
    for (size_t p = 0; p < e.size(); ++p) {
        const Rgb8 x = a.pixels[p];
        if (view == ViewerError::Flip) {
            e[p] = float(x.r) / 255.0f;
            continue;
        }
        const Rgb8 y = b.pixels[p];
        float sum = 0;
        for (auto [u, v] : {std::pair{x.r, y.r}, {x.g, y.g}, {x.b, y.b}})
            sum += view == ViewerError::Absolute
                       ? std::fabs(float(u) - float(v)) / 255.0f
                       : std::fabs(linear[u] - linear[v]) / (linear[v] + 0.01f);
        e[p] = sum / 3;
    }
    return e;
}

double openingErrorScale(const std::vector<std::vector<float>>& errors,
                         const std::vector<bool>& eligible, double percentile) {
    const bool any = std::find(eligible.begin(), eligible.end(), true) != eligible.end();
    const std::vector<float>* best = nullptr;
    double bestMean = INFINITY;
    for (size_t m = 0; m < errors.size(); ++m) {
        if ((any && !eligible[m]) || errors[m].empty()) continue;
        double sum = 0;
        for (float v : errors[m]) sum += v;
        if (sum / double(errors[m].size()) < bestMean)
            bestMean = sum / double(errors[m].size()), best = &errors[m];
    }
    if (!best) return 1;
    std::vector<float> e = *best;
    const size_t rank = size_t(std::ceil(percentile * double(e.size()) - 1e-9));
    const auto k = long(std::clamp<size_t>(rank, 1, e.size()) - 1);
    std::nth_element(e.begin(), e.begin() + k, e.end());
    return std::clamp(double(e[size_t(k)]), 1e-3, 10.0);
}

ViewerFrames::ViewerFrames(std::vector<std::string> names, int width, int height, int first,
                           int last, int shown, bool withFlip, int maxWidth, std::string outputDir,
                           int fps)
    : names_(std::move(names)), dir_(std::move(outputDir)), fullW_(width), fullH_(height),
      first_(first), shown_(shown), fps_(fps) {
    const int frameCount = last - first;
    const double budget = 12e6, methods = double(names_.size() - 1);
    const double columns = methods + 1 + (withFlip ? 0.5 * methods : 0);
    auto pixels = [&](int factor, int every) {
        return double(width / factor) * double(height / factor) * columns *
               double((frameCount + every - 1) / every + 1);
    };
    factor_ = std::max(1, int(std::ceil(double(width) / std::max(16, maxWidth))));
    while (pixels(factor_, every_) > budget && (frameCount + every_) / (every_ + 1) >= 8) ++every_;
    while (pixels(factor_, every_) > budget && factor_ < 64) ++factor_;
    images_.assign(names_.size(), {});
    flips_.assign(names_.size(), {});
    files_.assign(names_.size(), {});
    shownImages_.assign(names_.size(), Raster(0, 0));
    shownFlips_.assign(names_.size(), Raster(0, 0));
    fs::create_directories(fs::path(dir_) / "viewer");
}

void ViewerFrames::add(size_t column, int frame, const ImageF& linear, const ImageF* flipMap) {
    const Raster full = rasterFromLinear(linear);
    const std::string file =
        fmt::format("viewer/{}_{:04d}.png", fileStem(names_[column], column), frame);
    writePng((fs::path(dir_) / file).string(), full);
    if (!embeds(frame)) return;
    if (column == 0) frames_.push_back(frame);
    files_[column].push_back(file);
    Raster image = downscale(full, factor_);
    images_[column].push_back(dataUri(encodePng(image)));
    Raster flip = flipMap ? downscale(greyRaster(*flipMap), factor_) : Raster(0, 0);
    flips_[column].push_back(flipMap ? dataUri(encodePngGrey(flip)) : "");
    if (frame == shown_)
        shownImages_[column] = std::move(image), shownFlips_[column] = std::move(flip);
}

std::string ViewerFrames::json() const {
    nlohmann::json j;
    j["width"] = std::max(1, fullW_ / factor_), j["height"] = std::max(1, fullH_ / factor_);
    j["fullWidth"] = fullW_, j["fullHeight"] = fullH_;
    j["frames"] = frames_, j["every"] = every_, j["factor"] = factor_, j["shown"] = shown_;
    j["methods"] = names_;
    j["images"] = images_;
    nlohmann::json flips = nlohmann::json::array();
    for (const auto& perColumn : flips_) {
        nlohmann::json a = nlohmann::json::array();
        for (const std::string& f : perColumn)
            a.push_back(f.empty() ? nlohmann::json(nullptr) : nlohmann::json(f));
        flips.push_back(a);
    }
    j["flip"] = flips;
    j["full"] = files_;
    j["magma"] = heatStops();
    j["fps"] = fps_;
    // The error views open where the best method's error is visible: a fixed scale (0.5 once)
    // showed a good denoiser's error, a few hundredths, as black. The scale comes from the shown
    // frame as embedded, against the reference, the best of the methods other than the noisy
    // input; the viewer's scale slider still changes it.
    std::vector<bool> eligible;
    for (size_t c = 1; c < names_.size(); ++c) eligible.push_back(names_[c] != "noisy");
    auto scale = [&](ViewerError view) {
        std::vector<std::vector<float>> errors;
        for (size_t c = 1; c < names_.size(); ++c)
            errors.push_back(
                view == ViewerError::Flip && shownFlips_[c].pixels.empty()
                    ? std::vector<float>()
                    : viewerError(view == ViewerError::Flip ? shownFlips_[c] : shownImages_[c],
                                  shownImages_[0], view));
        return openingErrorScale(errors, eligible);
    };
    j["errorScale"] = {{"abs", scale(ViewerError::Absolute)},
                       {"rel", scale(ViewerError::Relative)},
                       {"flip", scale(ViewerError::Flip)}};
    // Inside <script>, "</script" or "<!--" would end or confuse the element: every '<', '>'
    // and '&' becomes a JSON \u escape.
    std::string text;
    for (char c : j.dump())
        text += c == '<'   ? std::string("\\u003c")
                : c == '>' ? std::string("\\u003e")
                : c == '&' ? std::string("\\u0026")
                           : std::string(1, c);
    return text;
}

} // namespace bmfr
