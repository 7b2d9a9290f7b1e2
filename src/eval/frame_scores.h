// Scores of one result frame against its reference. Colour spaces: RMSE, PSNR, SSIM, FLIP and
// the temporal error use the paper's display transform clamp(x^(1/2.2), 0, 1); relMSE uses
// linear HDR radiance.
#pragma once
#include "core/image.h"
#include <cmath>
#include <string>
#include <vector>

namespace bmfr {

struct FrameScores {
    double rmse = NAN, psnr = NAN, ssim = NAN, flip = NAN, relmse = NAN;
    double temporal = NAN; ///< against the previous result frame; NaN for the first frame
};

/// The metrics in table order. `key` names the metric in every machine-readable output
/// (`denoise`'s scores.csv and report.json, `eval`'s table.csv, per_frame.csv and table.json).
struct MetricInfo {
    const char* key;
    const char* label;
    bool lowerIsBetter;
    bool nonNegative; ///< plots start their axis at 0
};
const std::vector<MetricInfo>& metricList();
double metricValue(const FrameScores& s, const std::string& key);
/// A CSV cell: the value with 6 decimals, empty when missing (NaN), so that pandas reads numbers.
std::string csvNumber(double v);

/// Scores `result` (linear RGB) against `reference` (linear RGB); `previous` (may be null) is the
/// previous result frame, for the temporal error. `withFlip` switches the slowest metric;
/// `flipMapOut` (may be null) receives its per-pixel map.
FrameScores scoreFrame(const ImageF& result, const ImageF& reference, const ImageF* previous,
                       bool withFlip = true, ImageF* flipMapOut = nullptr);

/// Mean of each metric over frames (ignoring NaN).
FrameScores meanScores(const std::vector<FrameScores>& frames);

} // namespace bmfr
