#include "backend/cpu/cpu_taa.h"
#include "backend/cpu/modulation8.h"
#include "backend/cpu/taa_rows.h"
#include <algorithm>
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

// Per image row: a resolved row, then the row's previous pixel as two planes.
size_t rowFloats(int w) {
    return ResolvedRows::rowFloats(w) + 2 * ResolvedRows::pitch(w);
}

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

BMFR_SIMD_DISPATCH(void, resolveRows,
                   (const TaaCurrent& current, const float* previousPixel, float* scratch, int w,
                    TaaSpace space, long y0, long y1),
                   (current, previousPixel, scratch, w, space, y0, y1)) {
    const size_t pitch = ResolvedRows::pitch(w);
    for (long y = y0; y < y1; ++y) {
        float* row = scratch + size_t(y) * rowFloats(w);
        float* previous = row + ResolvedRows::rowFloats(w);
        for (int x = 0; x < w; x += 8) {
            const int n = std::min(8, w - x);
            const long i = y * w + x;
            f8 c[3], px, py;
            loadCurrent8(current, y, x, i, n, c);
            storeResolved8(row, pitch, x, c, space);
            loadXy8(previousPixel + 2 * i, n, px, py);
            store8(previous + x, px);
            store8(previous + pitch + x, py);
        }
        finishResolvedRow(row, pitch, w);
    }
}

BMFR_SIMD_DISPATCH(void, taaRows,
                   (const float* history, float* scratch, float* out, int w, int h, TaaBlend blend,
                    bool enabled, const uint8_t* accept, TaaSpace space, long y0, long y1),
                   (history, scratch, out, w, h, blend, enabled, accept, space, y0, y1)) {
    const size_t pitch = ResolvedRows::pitch(w), stride = rowFloats(w);
    for (long y = y0; y < y1; ++y) {
        const float* mid = scratch + size_t(y) * stride;
        const float* up = y > 0 ? mid - stride : mid;
        const float* down = y + 1 < h ? mid + stride : mid;
        const float* previous = mid + ResolvedRows::rowFloats(w);
        taaRow(up, mid, down, pitch, previous, previous + pitch, history, out + 3 * y * w, w, h,
               blend, enabled, accept ? accept + y * w : nullptr, space);
    }
}

} // namespace

size_t taaScratchFloats(int width, int height) {
    return size_t(height) * rowFloats(width);
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
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        resolveRows(current, previousPixel, scratch, w, space, y0, y1);
    });
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        taaRows(history, scratch, out, w, h, blend, enabled, accept, space, y0, y1);
    });
}

} // namespace bmfr::cpu
