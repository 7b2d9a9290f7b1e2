// `bmfr denoise`'s scores against a sequence's references: each frame of the result and of the
// noisy input scored as `eval` scores them (metricList's keys), written to scores.csv, added to
// report.json and printed as the summary.
#pragma once
#include "core/image.h"
#include "eval/frame_scores.h"
#include "io/sequence.h"
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bmfr::app {

class DenoiseScores {
  public:
    /// `flip`: also the FLIP metric (the slowest).
    DenoiseScores(int firstFrame, bool colorIsDemodulated, bool flip)
        : first_(firstFrame), demodulated_(colorIsDemodulated), flip_(flip) {}
    /// Scores frame `index`'s result against frame.reference, in frame order.
    void add(int index, const ImageF& result, const FrameData& frame);
    /// scores.csv: one row a frame, the metrics then the noisy input's and the reference's own.
    void writeCsv(const std::string& path) const;
    /// The means, into report["scores"].
    void addTo(nlohmann::json& report) const;
    /// The table printed after the run.
    std::string summary(const std::string& filter) const;

  private:
    int first_;
    bool demodulated_, flip_;
    std::vector<FrameScores> scores_, noisy_;
    std::vector<double> referenceTemporal_; ///< NaN for the first frame
    ImageF previousResult_, previousReference_, previousNoisy_;
    double referenceTemporalMean() const;
};

} // namespace bmfr::app
