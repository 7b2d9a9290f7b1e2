// Progress of a long job: a bar with rate and ETA on a terminal; otherwise a line every 10% of
// the work and, while a single step runs long, a line every 10 s; silent when quiet.
#pragma once
#include "core/stopwatch.h"
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace bmfr::app {

class Progress {
  public:
    Progress(std::string label, int total, bool quiet);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    void step(int done);
    /// Clears a terminal bar so that other output can be printed; the next step redraws it.
    void pause();
    void finish();

  private:
    void line(int done, const char* note); // the caller holds mutex_
    void heartbeat();

    std::string label_;
    int total_;
    bool quiet_, terminal_;
    Stopwatch clock_;
    double lastLineMs_ = -1e9;
    int lastLineDone_ = 0, done_ = 0;
    std::mutex mutex_;
    std::condition_variable wake_;
    bool stop_ = false;
    std::thread heartbeat_;
};

} // namespace bmfr::app
