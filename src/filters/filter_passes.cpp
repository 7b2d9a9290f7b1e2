#include "filters/filter_passes.h"
#include <atomic>

namespace bmfr {

int64_t countDiscarded(ThreadPool& pool, const uint8_t* accept, long pixels, bool hasHistory) {
    if (!hasHistory) return 0;
    std::atomic<int64_t> discarded{0};
    pool.parallelFor(pixels, 1 << 16, [&](long i0, long i1) {
        int64_t n = 0;
        for (long i = i0; i < i1; ++i) n += accept[i] == 0;
        discarded += n;
    });
    return discarded.load();
}

} // namespace bmfr
