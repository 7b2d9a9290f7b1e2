// The firefly clamp and the emitter mask share their BMFR_HD stages (filters/bmfr/) with every
// backend. Compiled without contracted multiply-adds
// (CMakeLists.txt), so that their luminances, and so their decisions, are the reference
// backend's bit for bit; flattened into each path's copy, so that those stages run on its vectors.
#include "backend/cpu/bmfr/cpu_block_masks.h"
#include "backend/cpu/simd.h"

namespace bmfr::cpu {

BMFR_SIMD_DISPATCH_FLAT(int, clampAndMaskBlock,
                        (const BlockMaskArgs& a, int bx, int by, float* columns, Scratch& sc),
                        (a, bx, by, columns, sc)) {
    const int B = a.grid.blockSize, M = a.featureCount;
    int quartile = -1; // the block's lower-quartile bucket, once the clamp has read it
    if (a.clampFireflies) {
        float* const z[3] = {columns + M * a.stride, columns + (M + 1) * a.stride,
                             columns + (M + 2) * a.stride};
        // Read for the few pixels the clamp scales only.
        auto length = [&](int k) {
            return blockFadeLength(a.grid, a.emitters, bx, by, k,
                                   [&](long i) { return a.noisy.at(3, size_t(i)); });
        };
        clampFireflies(B, z, sc.histogram.data(), sc.mask.data(), length, &quartile);
    }
    if (!a.emitters.on) return 0;
    return excludeEmitterRows(a.grid, a.in, a.emitters, bx, by, columns, M, a.stride,
                              sc.histogram.data(), sc.mask.data(), quartile);
}

} // namespace bmfr::cpu
