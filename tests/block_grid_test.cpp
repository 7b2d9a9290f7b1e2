// The displaced block grid covers every pixel exactly once, for every offset and odd sizes.
#include "filters/bmfr/block_grid.h"
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

void checkCoverage(int w, int h) {
    for (long frame = 0; frame < 16; ++frame) {
        BlockGrid g = makeBlockGrid(w, h, 32, frame);
        EXPECT_EQ(g.offsetX, kBlockOffsets[frame][0]);
        EXPECT_EQ(g.offsetY, kBlockOffsets[frame][1]);
        std::vector<int> owners(size_t(w) * h, 0);
        for (int by = 0; by < g.blocksY; ++by)
            for (int bx = 0; bx < g.blocksX; ++bx)
                for (int ly = 0; ly < 32; ++ly)
                    for (int lx = 0; lx < 32; ++lx) {
                        int x = g.originX(bx) + lx, y = g.originY(by) + ly;
                        // Every block pixel reads a valid (possibly mirrored) image pixel.
                        int mx = mirrorIndex(x, w), my = mirrorIndex(y, h);
                        ASSERT_TRUE(mx >= 0 && mx < w && my >= 0 && my < h);
                        if (x < 0 || y < 0 || x >= w || y >= h) continue;
                        ++owners[size_t(y) * w + x];
                        ASSERT_EQ(g.ownerX(x), bx);
                        ASSERT_EQ(g.ownerY(y), by);
                    }
        for (int c : owners) ASSERT_EQ(c, 1) << w << "x" << h << " frame " << frame;
    }
}

TEST(BlockGrid, EveryPixelInExactlyOneBlock) {
    checkCoverage(1, 1);
    checkCoverage(33, 17);
    checkCoverage(64, 32);
    checkCoverage(1281, 721);
}

TEST(BlockGrid, MirrorDuplicatesTheBorder) {
    // 3 2 1 0 | 0 1 2 3 | 3 2 1 0, as the authors' code.
    EXPECT_EQ(mirrorIndex(-1, 4), 0);
    EXPECT_EQ(mirrorIndex(-4, 4), 3);
    EXPECT_EQ(mirrorIndex(4, 4), 3);
    EXPECT_EQ(mirrorIndex(7, 4), 0);
    EXPECT_EQ(mirrorIndex(-40, 1), 0);
    EXPECT_EQ(mirrorIndex(2, 4), 2);
}

TEST(BlockGrid, OffsetsFollowTheAuthorsOrder) {
    EXPECT_EQ(makeBlockGrid(100, 100, 32, 0).offsetX, -14);
    EXPECT_EQ(makeBlockGrid(100, 100, 32, 1).offsetX, 4);
    EXPECT_EQ(makeBlockGrid(100, 100, 32, 15).offsetY, 4);
    EXPECT_EQ(makeBlockGrid(100, 100, 32, 16).offsetX, -14); // wraps after 16 frames
}

} // namespace
} // namespace bmfr
