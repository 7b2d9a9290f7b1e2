// The frames behind the report's viewer: every frame of every column (the reference, then the
// methods) written full size beside the report, and a budgeted subset embedded as PNG data
// URIs, with each method's FLIP map, for report_viewer.js; also the error scales the viewer's
// error views open at and the frame rate it plays at.
#pragma once
#include "core/image.h"
#include "eval/raster.h"
#include <string>
#include <vector>

namespace bmfr {

/// The viewer's error views, as report_viewer.js computes them per pixel from the embedded
/// 8-bit frames: A's error against B.
enum class ViewerError {
    Absolute, ///< |A - B| of the displayed values, mean of RGB
    Relative, ///< |A - B| / (B + 0.01) of the decoded linear values (x^2.2), mean of RGB
    Flip,     ///< A's FLIP map (grey levels / 255); B is not used
};
/// The per-pixel error of view `view` of `a` against `b`, as the viewer shows it; empty where
/// `b` is needed and its size differs.
std::vector<float> viewerError(const Raster& a, const Raster& b, ViewerError view);

/// The scale an error view opens at: the `percentile` (nearest rank) of the per-pixel error of
/// the best method, the one with the lowest mean error, maps to full brightness. `errors` holds
/// one map per method; only those with `eligible` set compete (all, when none is). Clamped to
/// the viewer's scale slider, [0.001, 10].
double openingErrorScale(const std::vector<std::vector<float>>& errors,
                         const std::vector<bool>& eligible, double percentile = 0.99);

class ViewerFrames {
  public:
    /// `names`: the columns; frames first..last-1; `shown` is where the viewer opens. Embeds
    /// frames at most `maxWidth` wide and about 12 M pixels in all (a FLIP map counts half):
    /// first every k-th frame (keeping at least 8, and `shown`), then smaller frames. The viewer
    /// plays the sequence at `fps` frames per second.
    ViewerFrames(std::vector<std::string> names, int width, int height, int first, int last,
                 int shown, bool withFlip, int maxWidth, std::string outputDir, int fps = 24);
    /// Writes viewer/<column>_<frame>.png and, for embedded frames, keeps the data URIs.
    void add(size_t column, int frame, const ImageF& linear, const ImageF* flipMap);
    /// The JSON that report_viewer.js reads, safe inside a <script> element.
    std::string json() const;

  private:
    std::vector<std::string> names_;
    std::string dir_;
    int fullW_, fullH_, first_, shown_, fps_;
    int factor_ = 1, every_ = 1;
    std::vector<int> frames_;
    std::vector<std::vector<std::string>> images_, flips_, files_; ///< [column][embedded frame]
    /// The shown frame as embedded, per column, for the opening error scales.
    std::vector<Raster> shownImages_, shownFlips_;
    bool embeds(int frame) const { return (frame - first_) % every_ == 0 || frame == shown_; }
};

} // namespace bmfr
