// Parallel loops over rows or blocks (oneTBB), with a thread-count limit per denoiser.
#pragma once
#include <functional>
#include <memory>

namespace bmfr {

/// Runs body(begin, end) over [0, count) split into chunks of at least `grain` items.
/// Each item must be independent: results are the same for any thread count.
class ThreadPool {
  public:
    explicit ThreadPool(int threads); ///< 0 = all cores
    ~ThreadPool();
    void parallelFor(long count, long grain, const std::function<void(long, long)>& body);
    int threadCount() const;
    /// Index of the calling worker inside parallelFor, in [0, threadCount()).
    static int currentThreadIndex();

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace bmfr
