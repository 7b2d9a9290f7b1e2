// The frames behind the report's viewer: every frame of every column (the reference, then the
// methods) written full size beside the report, and a budgeted subset embedded as PNG data
// URIs, with each method's FLIP map, for report_viewer.js.
#pragma once
#include "core/image.h"
#include <string>
#include <vector>

namespace bmfr {

class ViewerFrames {
  public:
    /// `names`: the columns; frames first..last-1; `shown` is where the viewer opens. Embeds
    /// frames at most `maxWidth` wide and about 12 M pixels in all (a FLIP map counts half):
    /// first every k-th frame (keeping at least 8, and `shown`), then smaller frames.
    ViewerFrames(std::vector<std::string> names, int width, int height, int first, int last,
                 int shown, bool withFlip, int maxWidth, std::string outputDir);
    /// Writes viewer/<column>_<frame>.png and, for embedded frames, keeps the data URIs.
    void add(size_t column, int frame, const ImageF& linear, const ImageF* flipMap);
    /// The JSON that report_viewer.js reads, safe inside a <script> element.
    std::string json() const;

  private:
    std::vector<std::string> names_;
    std::string dir_;
    int fullW_, fullH_, first_, shown_;
    int factor_ = 1, every_ = 1;
    std::vector<int> frames_;
    std::vector<std::vector<std::string>> images_, flips_, files_; ///< [column][embedded frame]
    bool embeds(int frame) const { return (frame - first_) % every_ == 0 || frame == shown_; }
};

} // namespace bmfr
