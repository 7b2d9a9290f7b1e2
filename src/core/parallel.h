// Parallel loops over rows or blocks (oneTBB), with a thread-count limit per denoiser.
#pragma once
#include <memory>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace bmfr {

/// A fixed set of worker threads. parallelFor runs body(begin, end) over [0, count) in chunks
/// of at least `grain` items; items must be independent, so results do not depend on the
/// thread count. A template, not std::function, so a frame's loops allocate nothing.
class ThreadPool {
  public:
    explicit ThreadPool(int threads); ///< 0 = all cores
    ~ThreadPool();

    template <typename Body> void parallelFor(long count, long grain, const Body& body) {
        if (count <= 0) return;
        arena().execute([&] {
            tbb::parallel_for(tbb::blocked_range<long>(0, count, grain > 0 ? grain : 1),
                              [&](const tbb::blocked_range<long>& r) { body(r.begin(), r.end()); });
        });
    }

    /// body(x, y) for every pixel of a width x height image, rows in chunks of `grainRows`.
    template <typename Body>
    void forEachPixel(int width, int height, long grainRows, const Body& body) {
        parallelFor(height, grainRows, [&](long y0, long y1) {
            for (long y = y0; y < y1; ++y)
                for (int x = 0; x < width; ++x) body(x, int(y));
        });
    }

    int threadCount() const;
    /// Index of the calling worker inside parallelFor, in [0, threadCount()).
    static int currentThreadIndex();

  private:
    tbb::task_arena& arena();
    std::unique_ptr<tbb::task_arena> arena_;
};

} // namespace bmfr
