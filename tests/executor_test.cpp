// The host executor (core/executor.h), which runs the reference backend's stages and whose
// loops the CUDA executor mirrors: every index and pixel visited once, on any thread count, and
// a frame counter's total independent of the order of its adds.
#include "core/executor.h"
#include <atomic>
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

TEST(HostExecutor, VisitsEveryIndexAndPixelOnceAndCountsAcrossThreads) {
    for (int threads : {1, 2, 5}) {
        SCOPED_TRACE(threads);
        ThreadPool pool(threads);
        const HostExecutor e{pool};
        const long n = 3 * 4096 + 17; // chunks of the grain and a ragged end
        std::vector<std::atomic<int>> seen(static_cast<size_t>(n));
        unsigned long long odd = 0;
        const FrameCounter counter{&odd};
        e.forEachIndex(n, [&](long i) {
            seen[size_t(i)] += 1;
            counter.add(i % 2);
        });
        for (long i = 0; i < n; ++i) ASSERT_EQ(seen[size_t(i)].load(), 1) << i;
        EXPECT_EQ(odd, unsigned(n / 2));

        const int w = 37, h = 23;
        std::vector<std::atomic<int>> pixels(size_t(w) * h);
        e.forEachPixel(
            w, h, [&](int x, int y) { pixels[size_t(y) * w + x] += 1; }, 3);
        for (const std::atomic<int>& p : pixels) ASSERT_EQ(p.load(), 1);
    }
}

} // namespace
} // namespace bmfr
