#include "backend/cpu/cpu_taa.h"
#include "backend/cpu/modulation8.h"
#include "backend/cpu/taa_rows.h"
#include <algorithm>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

/// The current frame's n <= 8 pixels from column x of row y (pixel i).
BMFR_SIMD_INLINE void loadCurrent8(const TaaCurrent& current, long y, int x, long i, int n,
                                   f8 c[3]) {
    if (!current.planes[0]) return loadXyz8(current.rgb + 3 * i, n, c);
    for (int k = 0; k < 3; ++k) c[k] = loadFirst(current.planes[k] + y * current.pitch + x, n);
    remodulate8(c, *current.in, i, n, true, current.albedoEpsilon);
}

/// The current frame as it is, packed (temporalAntiAliasing with enabled = false).
BMFR_SIMD_DISPATCH(void, copyRows, (const TaaCurrent& current, float* out, int w, long y0, long y1),
                   (current, out, w, y0, y1)) {
    for (long y = y0; y < y1; ++y)
        for (int x = 0; x < w; x += 8) {
            const int n = std::min(8, w - x);
            const long i = y * w + x;
            f8 c[3];
            loadCurrent8(current, y, x, i, n, c);
            storeXyz8(out + 3 * i, n, c);
        }
}

/// Image row y of the current frame into a resolved row, in TAA's space.
BMFR_SIMD_INLINE void resolveRow(const TaaCurrent& current, int w, TaaSpace space, long y,
                                 float* row) {
    const size_t pitch = ResolvedRows::pitch(w);
    for (int x = 0; x < w; x += 8) {
        f8 c[3];
        loadCurrent8(current, y, x, y * w + x, std::min(8, w - x), c);
        storeResolved8(row, pitch, x, c, space);
    }
    finishResolvedRow(row, pitch, w);
}

// A thread's scratch: three resolved rows (a ring: rows y - 1, y and y + 1), then row y's
// previous pixel as two planes.
size_t threadFloats(int w) {
    return 3 * ResolvedRows::rowFloats(w) + 2 * ResolvedRows::pitch(w);
}

/// TAA of rows [y0, y1) (ringRows, with the halo rows).
BMFR_SIMD_DISPATCH(void, taaRows,
                   (const TaaCurrent& current, const float* previousPixel, const float* history,
                    float* scratch, float* out, int w, int h, TaaBlend blend, const uint8_t* accept,
                    TaaSpace space, long y0, long y1),
                   (current, previousPixel, history, scratch, out, w, h, blend, accept, space, y0,
                    y1)) {
    const size_t pitch = ResolvedRows::pitch(w);
    float* previous = scratch + 3 * ResolvedRows::rowFloats(w);
    ringRows(
        scratch, w, h, y0, y1, true,
        [&] [[gnu::always_inline]] (long y, float* row) { resolveRow(current, w, space, y, row); },
        [&] [[gnu::always_inline]] (long y, const float* up, const float* mid, const float* down) {
            for (int x = 0; x < w; x += 8) {
                f8 px, py;
                loadXy8(previousPixel + 2 * (y * w + x), std::min(8, w - x), px, py);
                store8(previous + x, px);
                store8(previous + pitch + x, py);
            }
            taaRow(up, mid, down, pitch, previous, previous + pitch, history, out + 3 * y * w, w, h,
                   blend, true, accept ? accept + y * w : nullptr, space);
        });
}

} // namespace

size_t taaScratchFloats(int width, int threads) {
    return size_t(threads) * threadFloats(width);
}

void temporalAntiAliasing(ThreadPool& pool, const TaaCurrent& current, const float* history,
                          const float* previousPixel, float* scratch, float* out, int w, int h,
                          TaaBlend blend, bool enabled, const uint8_t* accept, TaaSpace space) {
    if (!enabled && !current.planes[0]) { // the current frame as it is
        std::memcpy(out, current.rgb, sizeof(float) * 3 * size_t(w) * size_t(h));
        return;
    }
    if (!enabled) {
        pool.parallelFor(h, 8, [&](long y0, long y1) { copyRows(current, out, w, y0, y1); });
        return;
    }
    const long tasks = (h + kRingRowsPerTask - 1) / kRingRowsPerTask;
    pool.parallelFor(tasks, 1, [&](long k0, long k1) {
        float* own = scratch + size_t(ThreadPool::currentThreadIndex()) * threadFloats(w);
        for (long k = k0; k < k1; ++k)
            taaRows(current, previousPixel, history, own, out, w, h, blend, accept, space,
                    k * kRingRowsPerTask, std::min<long>(h, (k + 1) * kRingRowsPerTask));
    });
}

} // namespace bmfr::cpu
