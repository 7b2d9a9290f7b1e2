// Terminal progress bar with rate and ETA; silent when quiet or when stderr is not a terminal.
#pragma once
#include <chrono>
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
    bool enabled_;
    std::chrono::steady_clock::time_point start_;
};

} // namespace bmfr::app
