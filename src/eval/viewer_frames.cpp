#include "eval/viewer_frames.h"
#include "eval/raster.h"
#include "eval/report_pictures.h"
#include <algorithm>
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

ViewerFrames::ViewerFrames(std::vector<std::string> names, int width, int height, int first,
                           int last, int shown, bool withFlip, int maxWidth, std::string outputDir)
    : names_(std::move(names)), dir_(std::move(outputDir)), fullW_(width), fullH_(height),
      first_(first), shown_(shown) {
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
    images_[column].push_back(dataUri(encodePng(downscale(full, factor_))));
    flips_[column].push_back(
        flipMap ? dataUri(encodePngGrey(downscale(greyRaster(*flipMap), factor_))) : "");
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
