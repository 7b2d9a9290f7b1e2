// TAA over a frame on an executor (core/executor.h), shared by every filter on the reference and
// CUDA backends: each pixel's YCoCg once, instead of nine times in its neighbours' clamps, then
// taaPixel; without history (or with TAA off) the input copied.
#pragma once
#include "core/executor.h"
#include "temporal/taa.h"

namespace bmfr {

/// `ycocg` holds 3 floats per pixel of scratch; `out` 3.
template <class Exec>
void taaStage(const Exec& e, const TaaInputs& in, float* ycocg, float* out, bool enabled) {
    const long n = long(in.width) * in.height;
    if (!enabled) {
        const float* from = in.current;
        e.forEachIndex(
            3 * n, BMFR_LAMBDA(long i) { out[i] = from[i]; });
        return;
    }
    const TaaInputs space = in;
    e.forEachIndex(
        n, BMFR_LAMBDA(long i) {
            store3(ycocg, i, rgbToYCoCg(taaSpace(space, load3(space.current, i))));
        });
    TaaInputs a = in;
    a.ycocg = ycocg;
    e.forEachPixel(
        in.width, in.height,
        BMFR_LAMBDA(int x, int y) { store3(out, long(y) * a.width + x, taaPixel(a, x, y)); });
}

} // namespace bmfr
