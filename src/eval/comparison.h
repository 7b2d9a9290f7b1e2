// The comparison behind `bmfr eval`: several result sequences scored against one reference
// sequence, written as tables (Markdown, CSV, JSON), per-frame plots, side-by-side crops, error
// heat maps and one self-contained HTML report.
#pragma once
#include "eval/frame_scores.h"
#include "io/range_parsers.h"
#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace bmfr {

struct MethodSource {
    std::string name;
    /// A `bmfr denoise` output folder (denoised_NNNN.exr) or a sequence folder (its noisy colour).
    std::string path;
};

struct ComparisonOptions {
    std::string reference; ///< sequence folder with reference frames
    /// Multilayer EXR layers of the reference sequence's buffers (`--channel`).
    std::map<std::string, std::string> referenceLayers;
    std::vector<MethodSource> methods;
    std::string output;
    std::string frames;                    ///< "A:B" (A..B-1); empty = all
    std::vector<std::array<int, 4>> crops; ///< x, y, w, h in pixels; empty = chosen by error
    int autoCrops = 2;                     ///< crops chosen by largest error when none are given
    int cropSize = 48;                     ///< pixels, for automatic crops
    int zoom = 4;                          ///< crop enlargement
    int showFrame = -1;                    ///< frame for pictures and heat maps; -1 = the last
    bool flip = true;
};

struct ComparisonResult {
    int first = 0, last = 0;
    std::vector<std::string> names;
    std::vector<std::vector<FrameScores>> perFrame; ///< [method][frame - first]
    std::vector<FrameScores> means;
    std::vector<double> referenceTemporal; ///< [frame - first], NaN for the first
    double referenceTemporalMean = NAN;
    std::string reportPath;
    std::string scoresJson; ///< the scores as written to table.json
};

/// Scores every method, writes every output; progress(done, total) per frame.
ComparisonResult runComparison(const ComparisonOptions& options,
                               const std::function<void(int, int)>& progress);

/// The score table as Markdown (best per column in bold).
std::string markdownTable(const ComparisonResult& r);

/// "A:B", "A:" or ":B" against a frame count. Throws bmfr::Error.
/// Text made safe for HTML element content and attribute values.
std::string escapeHtml(const std::string& text);

} // namespace bmfr
