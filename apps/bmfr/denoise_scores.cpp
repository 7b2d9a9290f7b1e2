#include "denoise_scores.h"
#include "io/atomic_file.h"
#include "metrics/basic_metrics.h"
#include <cmath>
#include <fmt/core.h>
#include <sstream>

namespace bmfr::app {

void DenoiseScores::add(int index, const ImageF& result, const FrameData& frame) {
    ImageF noisy = frame.color;
    if (demodulated_)
        for (size_t k = 0; k < noisy.pixels.size(); ++k) noisy.pixels[k] *= frame.albedo.pixels[k];
    const bool later = index > first_;
    const PreviousScoredFrame before{previousResult_, previousReference_};
    scores_.push_back(scoreFrame(result, frame.reference, later ? &before : nullptr, flip_));
    FrameScores n;
    n.rmse = rmseToneMapped(noisy, frame.reference);
    if (later) n.temporal = temporalError(noisy, previousNoisy_);
    noisy_.push_back(n);
    referenceTemporal_.push_back(later ? temporalError(frame.reference, previousReference_) : NAN);
    previousResult_ = result;
    previousReference_ = frame.reference;
    previousNoisy_ = std::move(noisy);
}

void DenoiseScores::writeCsv(const std::string& path) const {
    std::ostringstream csv;
    // The metric columns and keys of `bmfr eval`'s per_frame.csv, then the input's own.
    csv << "frame";
    for (const MetricInfo& m : metricList()) csv << "," << m.key;
    csv << ",noisy_rmse,noisy_temporal_error,reference_temporal_error\n";
    for (size_t k = 0; k < scores_.size(); ++k) {
        csv << first_ + int(k);
        for (const MetricInfo& m : metricList())
            csv << "," << csvNumber(metricValue(scores_[k], m.key));
        csv << "," << csvNumber(noisy_[k].rmse) << "," << csvNumber(noisy_[k].temporal) << ","
            << csvNumber(referenceTemporal_[k]) << "\n";
    }
    writeFileAtomically(path, csv.str());
}

double DenoiseScores::referenceTemporalMean() const {
    double sum = 0;
    int n = 0;
    for (double v : referenceTemporal_)
        if (std::isfinite(v)) sum += v, ++n;
    return n ? sum / n : NAN;
}

void DenoiseScores::addTo(nlohmann::json& report) const {
    const FrameScores m = meanScores(scores_), nm = meanScores(noisy_);
    auto num = [](double v) {
        return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
    };
    for (const MetricInfo& k : metricList()) report["scores"][k.key] = num(metricValue(m, k.key));
    report["scores"]["noisy_rmse"] = num(nm.rmse);
    report["scores"]["noisy_temporal_error"] = num(nm.temporal);
    report["scores"]["reference_temporal_error"] = num(referenceTemporalMean());
    report["scores"]["color_space"] = "tone-mapped: clamp(x^(1/2.2), 0, 1); relmse linear";
}

std::string DenoiseScores::summary(const std::string& filter) const {
    const FrameScores m = meanScores(scores_), nm = meanScores(noisy_);
    return fmt::format(
        "\nScores vs reference (mean over frames; tone-mapped x^(1/2.2), relMSE linear):\n"
        "  {:<10} {:>8} {:>8} {:>7} {:>7} {:>8} {:>13} {:>11}\n"
        "  {:<10} {:>8.4f} {:>8} {:>7} {:>7} {:>8} {:>13.4f} {:>11}\n"
        "  {:<10} {:>8.4f} {:>8.2f} {:>7.4f} {:>7} {:>8.4f} {:>13.4f} {:>11.4f}\n"
        "  {:<10} {:>8} {:>8} {:>7} {:>7} {:>8} {:>13.4f} {:>11}\n",
        "", "RMSE", "PSNR dB", "SSIM", "FLIP", "relMSE", "temporal err", "change err", "noisy",
        nm.rmse, "", "", "", "", nm.temporal, "", filter, m.rmse, m.psnr, m.ssim,
        std::isfinite(m.flip) ? fmt::format("{:.4f}", m.flip) : "-", m.relmse, m.temporal,
        m.temporalChange, "reference", "", "", "", "", "", referenceTemporalMean(), "");
}

} // namespace bmfr::app
