// History-poor pixels (BmfrSettings::secondGrid, the paper's future work): a pixel without
// history, on the first frame after a reset or where a disocclusion uncovered it, is fitted
// from one noisy sample per pixel, and the block edges show. It takes the mean of this frame's
// fit and a second fit on the grid moved by half a block, whose edges fall elsewhere. BMFR_HD:
// every backend runs its own fitter on secondGrid() and blends with these.
#pragma once
#include "filters/bmfr/block_grid.h"

namespace bmfr {

/// The frame's grid moved by half a block in x and y, the offsets kept in [-B/2, B/2).
BMFR_HD BlockGrid secondGrid(BlockGrid g) {
    const int B = g.blockSize, half = B / 2;
    g.offsetX = (g.offsetX + half + half) % B - half;
    g.offsetY = (g.offsetY + half + half) % B - half;
    return g;
}

/// A pixel that phase I found without history (history length 1).
BMFR_HD bool historyPoor(float historyLength) {
    return historyLength <= 1.0f;
}

/// The fitted colour of a history-poor pixel from the two grids' fits.
BMFR_HD float blendSecondFit(float first, float second) {
    return 0.5f * (first + second);
}

} // namespace bmfr
