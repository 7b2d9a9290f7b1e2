#include "progress.h"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace bmfr::app {

namespace {

/// Logs hear from a long step at least this often: 10 s, or BMFR_PROGRESS_HEARTBEAT_MS.
double heartbeatMs() {
    const char* env = std::getenv("BMFR_PROGRESS_HEARTBEAT_MS");
    const double v = env ? std::atof(env) : 0.0;
    return v > 0 ? v : 10000.0;
}

} // namespace

Progress::Progress(std::string label, int total, bool quiet)
    : label_(std::move(label)), total_(total), quiet_(quiet), terminal_(isatty(2)) {
    if (!quiet_ && !terminal_ && total_ > 0) heartbeat_ = std::thread([this] { heartbeat(); });
}

Progress::~Progress() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (heartbeat_.joinable()) heartbeat_.join();
}

void Progress::line(int done, const char* note) {
    const double ms = clock_.elapsed(), s = ms / 1000.0;
    const double rate = s > 0 ? done / s : 0, eta = rate > 0 ? (total_ - done) / rate : 0;
    if (note)
        std::fprintf(stderr, "%s: %d/%d, %s (%.0f s elapsed)\n", label_.c_str(), done, total_, note,
                     s);
    else
        std::fprintf(stderr, "%s: %d/%d (%.1f/s, ETA %.0fs)\n", label_.c_str(), done, total_, rate,
                     eta);
    std::fflush(stderr);
    lastLineMs_ = ms;
    lastLineDone_ = done;
}

void Progress::step(int done) {
    if (quiet_ || total_ <= 0) return;
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = done;
    const double ms = clock_.elapsed(), s = ms / 1000.0;
    if (terminal_) {
        const double rate = s > 0 ? done / s : 0, eta = rate > 0 ? (total_ - done) / rate : 0;
        const int width = 30, filled = done * width / total_;
        std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d  %.1f/s  ETA %.0fs ", label_.c_str(), filled,
                     "##############################", width - filled, "", done, total_, rate, eta);
        std::fflush(stderr);
        return;
    }
    // Logs and batch jobs: a line per tenth of the work, no more than one per 5 s.
    const bool tenth = (done - lastLineDone_) * 10 >= total_;
    if (done < total_ && (!tenth || ms - lastLineMs_ < 5000.0)) return;
    line(done, nullptr);
}

void Progress::heartbeat() {
    const double interval = heartbeatMs();
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop_) {
        wake_.wait_for(lock, std::chrono::milliseconds(std::min(1000, int(interval))));
        if (!stop_ && done_ < total_ && clock_.elapsed() - std::max(lastLineMs_, 0.0) >= interval)
            line(done_, "working");
    }
}

void Progress::pause() {
    if (quiet_ || !terminal_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    std::fprintf(stderr, "\r\033[K");
    std::fflush(stderr);
}

void Progress::finish() {
    if (quiet_) return;
    std::lock_guard<std::mutex> lock(mutex_);
    if (terminal_) std::fprintf(stderr, "\n");
    stop_ = true;
    wake_.notify_all();
}

} // namespace bmfr::app
