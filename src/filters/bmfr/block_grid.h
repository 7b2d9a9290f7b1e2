// The displaced grid of regression blocks: which image pixels form block (bx, by) this frame.
#pragma once
#include "core/border.h"
#include <bmfr/filters/bmfr_filter.h>

namespace bmfr {

/// The largest block edge BmfrSettings::blockSize allows, in pixels.
inline constexpr int kMaxBlockSize = 64;

/// Block grid of one frame. Block (bx, by) covers image pixels
/// [bx*B - B/2 + ox, +B) x [by*B - B/2 + oy, +B); pixels outside the image are mirrored in.
/// Every image pixel is "owned" (inside, unmirrored) by exactly one block.
struct BlockGrid {
    int blockSize = 32;
    int offsetX = 0, offsetY = 0;
    int blocksX = 0, blocksY = 0;
    int width = 0, height = 0;

    BMFR_HD int originX(int bx) const { return bx * blockSize - blockSize / 2 + offsetX; }
    BMFR_HD int originY(int by) const { return by * blockSize - blockSize / 2 + offsetY; }
    BMFR_HD int ownerX(int x) const { return (x + blockSize / 2 - offsetX) / blockSize; }
    BMFR_HD int ownerY(int y) const { return (y + blockSize / 2 - offsetY) / blockSize; }
    BMFR_HD int blockCount() const { return blocksX * blocksY; }
};

/// The image pixels block (bx, by) owns: [x0, x1) x [y0, y1), empty where it lies outside.
struct OwnedRect {
    int x0, x1, y0, y1;
    BMFR_HD bool empty() const { return x0 >= x1 || y0 >= y1; }
};

BMFR_HD int clampToRange(int v, int lo, int hi) {
    return v < lo ? lo : v > hi ? hi : v;
}

BMFR_HD OwnedRect ownedRect(const BlockGrid& g, int bx, int by) {
    const int ox = g.originX(bx), oy = g.originY(by), B = g.blockSize;
    return {clampToRange(ox, 0, g.width), clampToRange(ox + B, 0, g.width),
            clampToRange(oy, 0, g.height), clampToRange(oy + B, 0, g.height)};
}

/// Image pixel of pixel k (row-major) of block (bx, by), mirrored in at the border; `owned`
/// when the block owns it.
BMFR_HD long blockPixel(const BlockGrid& g, int bx, int by, int k, bool& owned) {
    const int ux = g.originX(bx) + k % g.blockSize, uy = g.originY(by) + k / g.blockSize;
    owned = ux >= 0 && ux < g.width && uy >= 0 && uy < g.height;
    return long(mirrorIndex(uy, g.height)) * g.width + mirrorIndex(ux, g.width);
}

/// Grid for frame `frameIndex` (offset = kBlockOffsets[frameIndex % 16], scaled to the block
/// size when it is not 32 so the displacement stays within half a block).
inline BlockGrid makeBlockGrid(int width, int height, int blockSize, long frameIndex) {
    BlockGrid g;
    g.blockSize = blockSize;
    g.width = width, g.height = height;
    const int* o = kBlockOffsets[frameIndex % 16];
    g.offsetX = o[0] * blockSize / 32;
    g.offsetY = o[1] * blockSize / 32;
    // ceil(size / B) + 1 blocks cover [0, size) for every offset in [-B/2, B/2).
    g.blocksX = (width + blockSize - 1) / blockSize + 1;
    g.blocksY = (height + blockSize - 1) / blockSize + 1;
    return g;
}

} // namespace bmfr
