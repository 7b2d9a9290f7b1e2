// The videos of a comparison: methods.mp4 (the reference and the methods side by side,
// labelled) and flicker.mp4 (each method's frame-to-frame change, x4), at most 1920 pixels wide.
#pragma once
#include "eval/video.h"
#include <memory>
#include <string>
#include <vector>

namespace bmfr {

class ComparisonVideos {
  public:
    /// `names`: the methods; frames are `width` pixels wide. Throws when ffmpeg will not start.
    ComparisonVideos(const std::string& ffmpeg, const std::string& outputDir, int fps,
                     std::vector<std::string> names, int width);
    /// One frame: the reference and each method; `previous` is empty for the first frame.
    void add(const ImageF& reference, const std::vector<ImageF>& methods,
             const std::vector<ImageF>& previous);
    /// Waits for ffmpeg; returns the files written.
    std::vector<std::string> finish();

  private:
    std::vector<std::string> names_;
    std::string dir_;
    int factor_ = 1;
    std::unique_ptr<VideoWriter> sideBySide_, flicker_;
};

} // namespace bmfr
