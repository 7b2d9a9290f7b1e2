#include "backend/cpu/cpu_taa.h"
#include "backend/cpu/taa_rows.h"
#include <cstring>

namespace bmfr::cpu {

using namespace simd;

namespace {

// Per image row: a resolved row, then the row's previous pixel as two planes.
size_t rowFloats(int w) {
    return ResolvedRows::rowFloats(w) + 2 * ResolvedRows::pitch(w);
}

BMFR_SIMD_DISPATCH(void, resolveRows,
                   (const float* current, const float* previousPixel, float* scratch, int w,
                    TaaSpace space, long y0, long y1),
                   (current, previousPixel, scratch, w, space, y0, y1)) {
    const size_t pitch = ResolvedRows::pitch(w);
    for (long y = y0; y < y1; ++y) {
        float* row = scratch + size_t(y) * rowFloats(w);
        float* previous = row + ResolvedRows::rowFloats(w);
        for (int x = 0; x < w; x += 8) {
            const int n = std::min(8, w - x);
            const long i = y * w + x;
            f8 c[3];
            loadXyz8(current + 3 * i, n, c);
            storeResolved8(row, pitch, x, c, space);
            float pp[16] = {};
            std::memcpy(pp, previousPixel + 2 * i, sizeof(float) * 2 * size_t(n));
            for (int l = 0; l < 8; ++l)
                previous[x + l] = pp[2 * l], previous[pitch + x + l] = pp[2 * l + 1];
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

void temporalAntiAliasing(ThreadPool& pool, const float* current, const float* history,
                          const float* previousPixel, float* scratch, float* out, int w, int h,
                          TaaBlend blend, bool enabled, const uint8_t* accept, TaaSpace space) {
    if (!enabled) { // the current frame as it is (the passes below would copy it too)
        std::memcpy(out, current, sizeof(float) * 3 * size_t(w) * size_t(h));
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
