// The one wall clock of the library: stage times in milliseconds.
#pragma once
#include <chrono>

namespace bmfr {

/// Starts on construction; lap() returns the milliseconds since the last lap (or the start).
class Stopwatch {
  public:
    using Clock = std::chrono::steady_clock;
    Stopwatch() : last_(Clock::now()) {}
    double lap() {
        const Clock::time_point now = Clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
        last_ = now;
        return ms;
    }
    /// Milliseconds since the last lap, without starting a new one.
    double elapsed() const {
        return std::chrono::duration<double, std::milli>(Clock::now() - last_).count();
    }
    /// Nanoseconds between two points, for workers that sum their own time.
    static long long nanoseconds(Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration_cast<std::chrono::nanoseconds>(b - a).count();
    }

  private:
    Clock::time_point last_;
};

} // namespace bmfr
