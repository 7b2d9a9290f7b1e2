// Scores of one result frame against its reference. Colour spaces: RMSE, PSNR, SSIM, FLIP and
// the temporal and change errors use the paper's display transform clamp(x^(1/2.2), 0, 1);
// relMSE uses linear HDR radiance.
#pragma once
#include "core/image.h"
#include <cmath>
#include <string>
#include <vector>

namespace bmfr {

struct FrameScores {
    double rmse = NAN, psnr = NAN, ssim = NAN, flip = NAN, relmse = NAN;
    double temporal = NAN; ///< against the previous result frame; NaN for the first frame
    /// Error of the frame-to-frame change against the reference's (temporalChangeError); NaN
    /// for the first frame.
    double temporalChange = NAN;
};

/// The metrics in table order. `key` names the metric in every machine-readable output
/// (`denoise`'s scores.csv and report.json, `eval`'s table.csv, per_frame.csv and table.json).
struct MetricInfo {
    const char* key;
    const char* label;
    bool lowerIsBetter;
    bool nonNegative; ///< plots start their axis at 0
    /// The reference sequence has its own value, and that is the target: neither lower nor
    /// higher is better (the temporal error, which counts the scene's real motion too).
    bool referenceIsTarget = false;
};
const std::vector<MetricInfo>& metricList();
double metricValue(const FrameScores& s, const std::string& key);
/// A CSV cell: the value with 6 decimals, empty when missing (NaN), so that pandas reads numbers.
std::string csvNumber(double v);

/// The previous frame's result and reference, for the temporal errors.
struct PreviousScoredFrame {
    const ImageF& result;
    const ImageF& reference;
};

/// Scores `result` (linear RGB) against `reference` (linear RGB); `previous` (null for the first
/// frame) gives the temporal errors. `withFlip` switches the slowest metric; `flipMapOut` (may be
/// null) receives its per-pixel map.
FrameScores scoreFrame(const ImageF& result, const ImageF& reference,
                       const PreviousScoredFrame* previous, bool withFlip = true,
                       ImageF* flipMapOut = nullptr);

/// Mean of each metric over frames (ignoring NaN).
FrameScores meanScores(const std::vector<FrameScores>& frames);

} // namespace bmfr
