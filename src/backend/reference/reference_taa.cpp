#include "backend/reference/reference_taa.h"
#include <cstring>

namespace bmfr::reference {

void taaPass(ThreadPool& pool, const TaaInputs& in, float* ycocg, float* out, bool enabled) {
    const int w = in.width, h = in.height;
    if (!enabled) {
        std::memcpy(out, in.current, size_t(w) * size_t(h) * 3 * sizeof(float));
        return;
    }
    // Each pixel's YCoCg once, instead of nine times in its neighbours' clamps.
    pool.parallelFor(h, 8, [&](long y0, long y1) {
        for (long i = y0 * w; i < y1 * w; ++i)
            store3(ycocg, i, rgbToYCoCg(taaSpace(in, load3(in.current, i))));
    });
    TaaInputs a = in;
    a.ycocg = ycocg;
    pool.parallelFor(h, 4, [&](long y0, long y1) {
        for (long y = y0; y < y1; ++y)
            for (int x = 0; x < w; ++x) store3(out, y * w + x, taaPixel(a, x, int(y)));
    });
}

} // namespace bmfr::reference
