// The comparison behind `bmfr eval`: several result sequences scored against one reference
// sequence, written as tables (Markdown, CSV, JSON), per-frame plots (SVG and PNG), side-by-side
// insets, error heat maps, optional videos, and one self-contained HTML report with an
// interactive viewer and the run's metadata.
#pragma once
#include "eval/escape_html.h"
#include "eval/frame_scores.h"
#include "eval/run_metadata.h"
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
    int autoCrops = 3;  ///< insets chosen where methods differ, when none are given
    int cropSize = 48;  ///< pixels, for automatic crops
    int zoom = 4;       ///< crop enlargement
    int showFrame = -1; ///< frame for pictures and heat maps; -1 = the last
    bool flip = true;
    std::string logPlots = "auto"; ///< "auto" (log y where values span > 10x), "on" or "off"
    bool video = false;            ///< methods.mp4 and flicker.mp4 through ffmpeg
    int videoFps = 24;             ///< frames per second of the videos and the viewer's playback
    int viewerWidth = 640;         ///< pixels; wider frames are embedded downscaled
    std::string commandLine;       ///< for the report's run section
    std::string programVersion;    ///< for the report's run section
};

struct ComparisonResult {
    int first = 0, last = 0;
    std::vector<std::string> names;
    std::vector<std::vector<FrameScores>> perFrame; ///< [method][frame - first]
    std::vector<FrameScores> means;
    /// [method]: what its run recorded (report.json): filter, settings, ms per frame, machine.
    std::vector<MethodMetadata> runs;
    std::vector<double> referenceTemporal; ///< [frame - first], NaN for the first
    double referenceTemporalMean = NAN;
    std::string reportPath;
    std::string scoresJson;                ///< the scores as written to table.json
    std::vector<std::array<int, 4>> crops; ///< the insets shown
    std::vector<std::string> videos;       ///< the videos written
};

/// Scores every method, writes every output; progress(done, total) per frame. With `video` but
/// no ffmpeg on PATH, everything else is written and then bmfr::Error says so.
ComparisonResult runComparison(const ComparisonOptions& options,
                               const std::function<void(int, int)>& progress);

} // namespace bmfr
