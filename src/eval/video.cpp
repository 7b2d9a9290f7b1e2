#include "eval/video.h"
#include "io/atomic_file.h"
#include "io/shell_quote.h"
#include <bmfr/error.h>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fmt/core.h>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace bmfr {

namespace fs = std::filesystem;

std::string findFfmpeg() {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        if (dir.empty()) continue;
        const fs::path candidate = fs::path(dir) / "ffmpeg";
        if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
    return {};
}

VideoWriter::VideoWriter(const std::string& ffmpeg, const std::string& path, int fps)
    : ffmpeg_(ffmpeg), path_(path), partial_(temporaryPathFor(path)), fps_(fps) {}

VideoWriter::~VideoWriter() {
    if (pipe_) {
        ::pclose(pipe_);
        std::error_code ec;
        fs::remove(partial_, ec);
    }
}

void VideoWriter::add(const Raster& frame) {
    if (!pipe_) {
        width_ = frame.width + frame.width % 2, height_ = frame.height + frame.height % 2;
        // yuv420p (what players expect) needs even sizes; -crf 18 is visually lossless.
        const std::string cmd = fmt::format(
            "{} -hide_banner -loglevel error -y -f rawvideo -pix_fmt rgb24 -s {}x{} -r {} -i - "
            "-c:v libx264 -preset medium -crf 18 -pix_fmt yuv420p -movflags +faststart -f mp4 {}",
            shellQuote(ffmpeg_), width_, height_, fps_, shellQuote(partial_));
        std::signal(SIGPIPE, SIG_IGN); // a failed ffmpeg is an error from fwrite, not a kill
        pipe_ = ::popen(cmd.c_str(), "w");
        if (!pipe_) throw Error("eval --video: cannot start " + ffmpeg_);
    }
    Raster padded(width_, height_, Rgb8{0, 0, 0});
    padded.blit(frame, 0, 0);
    if (std::fwrite(padded.pixels.data(), 3, padded.pixels.size(), pipe_) != padded.pixels.size())
        throw Error("eval --video: ffmpeg stopped reading frames for " + path_);
}

void VideoWriter::finish() {
    if (!pipe_) throw Error("eval --video: no frames for " + path_);
    const int status = ::pclose(pipe_);
    pipe_ = nullptr;
    if (status != 0 || !fs::exists(partial_)) {
        std::error_code ec;
        fs::remove(partial_, ec);
        throw Error(fmt::format("eval --video: ffmpeg failed writing {} (exit status {})", path_,
                                WIFEXITED(status) ? WEXITSTATUS(status) : status));
    }
    commitTemporary(partial_, path_);
}

} // namespace bmfr
