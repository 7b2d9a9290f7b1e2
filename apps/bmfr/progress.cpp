#include "progress.h"
#include <cstdio>
#include <unistd.h>

namespace bmfr::app {

Progress::Progress(std::string label, int total, bool quiet)
    : label_(std::move(label)), total_(total), quiet_(quiet), terminal_(isatty(2)) {}

void Progress::step(int done) {
    if (quiet_ || total_ <= 0) return;
    const double ms = clock_.elapsed(), s = ms / 1000.0;
    const double rate = s > 0 ? done / s : 0, eta = rate > 0 ? (total_ - done) / rate : 0;
    if (terminal_) {
        const int width = 30, filled = done * width / total_;
        std::fprintf(stderr, "\r%s [%.*s%*s] %d/%d  %.1f/s  ETA %.0fs ", label_.c_str(), filled,
                     "##############################", width - filled, "", done, total_, rate, eta);
        std::fflush(stderr);
        return;
    }
    // Logs and batch jobs: a line per tenth of the work, no more than one per 5 s.
    const bool tenth = (done - lastLineDone_) * 10 >= total_;
    if (done < total_ && (!tenth || ms - lastLineMs_ < 5000.0)) return;
    std::fprintf(stderr, "%s: %d/%d (%.1f/s, ETA %.0fs)\n", label_.c_str(), done, total_, rate,
                 eta);
    lastLineMs_ = ms;
    lastLineDone_ = done;
}

void Progress::finish() {
    if (!quiet_ && terminal_) std::fprintf(stderr, "\n");
}

} // namespace bmfr::app
