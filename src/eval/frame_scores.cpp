#include "eval/frame_scores.h"
#include "metrics/basic_metrics.h"
#include "metrics/flip.h"
#include "metrics/ssim.h"
#include <fmt/core.h>

namespace bmfr {

const std::vector<MetricInfo>& metricList() {
    static const std::vector<MetricInfo> list = {
        {"rmse", "RMSE", true, true},
        {"psnr_db", "PSNR dB", false, false},
        {"ssim", "SSIM", false, false},
        {"flip", "FLIP", true, true},
        {"relmse", "relMSE", true, true},
        {"temporal_error", "temporal error", true, true, true},
        {"temporal_change_error", "change error", true, true}};
    return list;
}

namespace {
template <class Scores> auto& metricRef(Scores& s, const std::string& key) {
    if (key == "rmse") return s.rmse;
    if (key == "psnr_db") return s.psnr;
    if (key == "ssim") return s.ssim;
    if (key == "flip") return s.flip;
    if (key == "relmse") return s.relmse;
    if (key == "temporal_change_error") return s.temporalChange;
    return s.temporal;
}
} // namespace

double metricValue(const FrameScores& s, const std::string& key) {
    return metricRef(s, key);
}

std::string csvNumber(double v) {
    return std::isfinite(v) ? fmt::format("{:.6f}", v) : std::string();
}

FrameScores scoreFrame(const ImageF& result, const ImageF& reference,
                       const PreviousScoredFrame* previous, bool withFlip, ImageF* flipMapOut) {
    FrameScores s;
    const ImageF a = toneMapped(result), r = toneMapped(reference);
    s.rmse = rmseLinear(a, r);
    s.psnr = psnr(a, r);
    s.ssim = ssim(a, r);
    if (withFlip) {
        ImageF map = flipMap(r, a);
        s.flip = flipMean(map);
        if (flipMapOut) *flipMapOut = std::move(map);
    }
    s.relmse = relMseLinear(result, reference);
    if (previous) {
        s.temporal = temporalError(result, previous->result);
        s.temporalChange =
            temporalChangeError(result, previous->result, reference, previous->reference);
    }
    return s;
}

FrameScores meanScores(const std::vector<FrameScores>& frames) {
    FrameScores m;
    for (const MetricInfo& info : metricList()) {
        double sum = 0;
        int n = 0;
        for (const FrameScores& f : frames) {
            double v = metricValue(f, info.key);
            if (std::isfinite(v)) sum += v, ++n;
        }
        metricRef(m, info.key) = n ? sum / n : NAN;
    }
    return m;
}

} // namespace bmfr
