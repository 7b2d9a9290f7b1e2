#include "eval/comparison_videos.h"
#include "core/color.h"
#include "eval/report_pictures.h"
#include <algorithm>
#include <cmath>
#include <filesystem>

namespace bmfr {

namespace fs = std::filesystem;

ComparisonVideos::ComparisonVideos(const std::string& ffmpeg, const std::string& outputDir, int fps,
                                   std::vector<std::string> names, int width)
    : names_(std::move(names)), dir_(outputDir) {
    sideBySide_ =
        std::make_unique<VideoWriter>(ffmpeg, (fs::path(dir_) / "methods.mp4").string(), fps);
    flicker_ =
        std::make_unique<VideoWriter>(ffmpeg, (fs::path(dir_) / "flicker.mp4").string(), fps);
    const int columns = int(names_.size()) + 1;
    while (columns * (width / factor_ + 8) > 1920 && factor_ < 16) ++factor_;
}

void ComparisonVideos::add(const ImageF& reference, const std::vector<ImageF>& methods,
                           const std::vector<ImageF>& previous) {
    std::vector<const ImageF*> row{&reference};
    std::vector<std::string> labels{"reference"};
    std::vector<ImageF> change;
    std::vector<std::string> changeLabels;
    for (size_t m = 0; m < methods.size(); ++m) {
        row.push_back(&methods[m]), labels.push_back(names_[m]);
        ImageF d(reference.width, reference.height, 3);
        if (!previous.empty() && previous[m].width)
            for (size_t k = 0; k < d.pixels.size(); ++k) {
                // x4 so that flicker shows; stored linear, so undo the display encoding.
                const float e = 4.0f * std::fabs(gammaEncode(methods[m].pixels[k]) -
                                                 gammaEncode(previous[m].pixels[k]));
                d.pixels[k] = std::pow(std::min(e, 1.0f), 2.2f);
            }
        change.push_back(std::move(d));
        changeLabels.push_back(names_[m] + " |dt| x4");
    }
    sideBySide_->add(downscale(labelledRow(row, labels), factor_));
    std::vector<const ImageF*> changeRow;
    for (const ImageF& d : change) changeRow.push_back(&d);
    flicker_->add(downscale(labelledRow(changeRow, changeLabels), factor_));
}

std::vector<std::string> ComparisonVideos::finish() {
    sideBySide_->finish();
    flicker_->finish();
    return {(fs::path(dir_) / "methods.mp4").string(), (fs::path(dir_) / "flicker.mp4").string()};
}

} // namespace bmfr
