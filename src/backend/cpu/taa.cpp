#include "backend/cpu/taa.h"
#include "backend/cpu/taa_rows.h"

namespace bmfr::cpu {

namespace {

BMFR_SIMD_CLONES void taaRows(const float* history, const float* previousPixel, float* records,
                              float* out, int w, int h, float alpha, bool enabled, long y0,
                              long y1) {
    for (long y = y0; y < y1; ++y) {
        const float* up = records + 8 * size_t(y > 0 ? y - 1 : y) * size_t(w);
        const float* mid = records + 8 * size_t(y) * size_t(w);
        const float* down = records + 8 * size_t(y + 1 < h ? y + 1 : y) * size_t(w);
        taaRow(up, mid, down, history, previousPixel + 2 * y * w, out + 3 * y * w, w, h, alpha,
               enabled);
    }
}

} // namespace

void temporalAntiAliasing(ThreadPool& pool, const float* current, const float* history,
                          const float* previousPixel, float* records, float* out, int w, int h,
                          float alpha, bool enabled) {
    const long n = long(w) * h;
    pool.parallelFor(n, 4096, [&](long i0, long i1) {
        for (long i = i0; i < i1; ++i)
            storeResolved(records + 8 * i,
                          simd::f4{current[3 * i], current[3 * i + 1], current[3 * i + 2], 0.0f});
    });
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        taaRows(history, previousPixel, records, out, w, h, alpha, enabled, y0, y1);
    });
}

} // namespace bmfr::cpu
