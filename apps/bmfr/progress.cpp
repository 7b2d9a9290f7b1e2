#include "progress.h"
#include <cstdio>
#include <unistd.h>

namespace bmfr::app {

Progress::Progress(std::string label, int total, bool quiet)
    : label_(std::move(label)), total_(total), enabled_(!quiet && isatty(2)),
      start_(std::chrono::steady_clock::now()) {}

void Progress::step(int done) {
    if (!enabled_ || total_ <= 0) return;
    const double s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int width = 30, filled = done * width / total_;
    const double rate = s > 0 ? done / s : 0, eta = rate > 0 ? (total_ - done) / rate : 0;
    std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d  %.1f/s  ETA %.0fs ", label_.c_str(), filled,
                 "##############################", width - filled, "", done, total_, rate, eta);
    std::fflush(stderr);
}

void Progress::finish() {
    if (enabled_) std::fprintf(stderr, "\n");
}

} // namespace bmfr::app
