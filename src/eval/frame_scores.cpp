#include "eval/frame_scores.h"
#include "metrics/basic_metrics.h"
#include "metrics/flip.h"
#include "metrics/ssim.h"

namespace bmfr {

const std::vector<MetricInfo>& metricList() {
    static const std::vector<MetricInfo> list = {
        {"rmse", "RMSE", true}, {"psnr", "PSNR dB", false}, {"ssim", "SSIM", false},
        {"flip", "FLIP", true}, {"relmse", "relMSE", true}, {"temporal", "temporal error", true}};
    return list;
}

double metricValue(const FrameScores& s, const std::string& key) {
    if (key == "rmse") return s.rmse;
    if (key == "psnr") return s.psnr;
    if (key == "ssim") return s.ssim;
    if (key == "flip") return s.flip;
    if (key == "relmse") return s.relmse;
    return s.temporal;
}

FrameScores scoreFrame(const ImageF& result, const ImageF& reference, const ImageF* previous,
                       bool withFlip) {
    FrameScores s;
    const ImageF a = toneMapped(result), r = toneMapped(reference);
    s.rmse = rmseLinear(a, r);
    s.psnr = psnr(a, r);
    s.ssim = ssim(a, r);
    if (withFlip) s.flip = flip(r, a);
    s.relmse = relMseLinear(result, reference);
    if (previous) s.temporal = temporalError(result, *previous);
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
        double mean = n ? sum / n : NAN;
        std::string k = info.key;
        (k == "rmse"     ? m.rmse
         : k == "psnr"   ? m.psnr
         : k == "ssim"   ? m.ssim
         : k == "flip"   ? m.flip
         : k == "relmse" ? m.relmse
                         : m.temporal) = mean;
    }
    return m;
}

} // namespace bmfr
