// H.264 MP4 output through Debian's ffmpeg: raw RGB frames piped to its stdin.
#pragma once
#include "eval/raster.h"
#include <cstdio>
#include <string>

namespace bmfr {

/// The ffmpeg executable on PATH, or empty.
std::string findFfmpeg();

/// One video being written; frames must all have the first frame's size (even sizes are padded).
/// The file appears under its name only once ffmpeg has finished it.
class VideoWriter {
  public:
    /// Throws bmfr::Error when ffmpeg cannot be started.
    VideoWriter(const std::string& ffmpeg, const std::string& path, int fps);
    ~VideoWriter();
    VideoWriter(const VideoWriter&) = delete;
    VideoWriter& operator=(const VideoWriter&) = delete;
    void add(const Raster& frame);
    /// Waits for ffmpeg; throws bmfr::Error naming the file if it failed.
    void finish();

  private:
    std::string ffmpeg_, path_, partial_;
    int fps_ = 24, width_ = 0, height_ = 0;
    FILE* pipe_ = nullptr;
};

} // namespace bmfr
