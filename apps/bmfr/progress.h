// Progress of a long job: a bar with rate and ETA on a terminal, a line every 10% (and at most
// every 5 s) otherwise; silent when quiet.
#pragma once
#include "core/stopwatch.h"
#include <string>

namespace bmfr::app {

class Progress {
  public:
    Progress(std::string label, int total, bool quiet);
    void step(int done);
    void finish();

  private:
    std::string label_;
    int total_;
    bool quiet_, terminal_;
    Stopwatch clock_;
    double lastLineMs_ = -1e9;
    int lastLineDone_ = 0;
};

} // namespace bmfr::app
