// History-poor pixels fitted twice (BmfrSettings::secondGrid, filters/bmfr/second_grid.h): the
// shifted grid against hand values, and a frame without history against the mean of two plain
// fits on the two grids, each taken from its own frame of the same filter.
#include "filters/bmfr/second_grid.h"
#include "io/sequence.h"
#include "synth/procedural_scene.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <gtest/gtest.h>
#include <vector>

namespace bmfr {
namespace {

TEST(SecondGrid, IsTheFramesGridMovedByHalfABlock) {
    // Frame 0's offset (-14, -14) moves to (2, 2); frame 1's (4, -6) to (-12, 10), wrapped.
    BlockGrid g = makeBlockGrid(100, 60, 32, 0);
    BlockGrid s = secondGrid(g);
    EXPECT_EQ(s.offsetX, 2);
    EXPECT_EQ(s.offsetY, 2);
    EXPECT_EQ(s.blocksX, g.blocksX);
    g = makeBlockGrid(100, 60, 32, 1);
    s = secondGrid(g);
    EXPECT_EQ(s.offsetX, -12);
    EXPECT_EQ(s.offsetY, 10);
    // Frame 3's grid, (8, 0), moved is frame 9's, (-8, -16).
    s = secondGrid(makeBlockGrid(100, 60, 32, 3));
    const BlockGrid nine = makeBlockGrid(100, 60, 32, 9);
    EXPECT_EQ(s.offsetX, nine.offsetX);
    EXPECT_EQ(s.offsetY, nine.offsetY);
    // Block size 8: offsets scale to [-4, 4).
    s = secondGrid(makeBlockGrid(40, 30, 8, 0));
    EXPECT_EQ(makeBlockGrid(40, 30, 8, 0).offsetX, -3);
    EXPECT_EQ(s.offsetX, 1);
}

TEST(SecondGrid, APixelWithoutHistoryTakesTheMeanOfBothGridsFits) {
    // Frame 3 with its normals flipped loses every history tap (the normal test), so all its
    // pixels are history-poor. Its fit is the same as a fresh frame's: a flipped linear
    // feature spans the same columns. Without regularisation noise the fit depends on the
    // frame index only through the grid, so frame 9 given the same input is the plain fit on
    // frame 3's second grid.
    ProceduralSceneOptions o;
    o.width = 70, o.height = 45, o.frames = 10;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(10);
    for (int i = 0; i < 10; ++i) scene.render(i, frames[size_t(i)]);
    FrameData lost = frames[3];
    for (float& v : lost.normal.pixels) v = -v;

    auto run = [&](bool second, int until) {
        auto f = makeFilter("bmfr", {{"backend", "reference"},
                                     {"noiseAmplitude", "0"},
                                     {"halfHistory", "false"},
                                     {"secondGrid", second ? "true" : "false"}});
        f->setDebugOutputs(true);
        std::vector<std::vector<float>> fitted, length;
        for (int i = 0; i <= until; ++i) {
            f->denoise(i == 3 || i == 9 ? lost.input() : frames[size_t(i)].input());
            const ImageView v = f->debug().fitted, len = f->debug().historyLength;
            fitted.emplace_back(v.data, v.data + long(v.width) * v.height * 3);
            length.emplace_back(len.data, len.data + long(len.width) * len.height);
            if (i == 3 || i == 9) {
                for (float n : length.back()) EXPECT_EQ(n, 1.0f) << "frame " << i;
            }
        }
        return std::pair{fitted, length};
    };
    const auto [both, bothLength] = run(true, 3);
    const auto [plain, plainLength] = run(false, 9);
    double worst = 0.0, moved = 0.0;
    for (size_t k = 0; k < both[3].size(); ++k) {
        const double expected = 0.5 * (double(plain[3][k]) + plain[9][k]);
        worst = std::max(worst, std::fabs(both[3][k] - expected) - 1e-4 * std::fabs(expected));
        moved = std::max(moved, std::fabs(double(plain[3][k]) - plain[9][k]));
    }
    EXPECT_LE(worst, 1e-5);
    EXPECT_GT(moved, 1e-2) << "the two grids' fits should differ";
    // A pixel with history keeps its one fit: frame 2's are the same bits with and without.
    long kept = 0;
    for (size_t p = 0; p < bothLength[2].size(); ++p) {
        if (bothLength[2][p] <= 1.0f) continue;
        ++kept;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(both[2][3 * p + c], plain[2][3 * p + c]) << p;
    }
    EXPECT_GT(kept, long(bothLength[2].size()) / 2);
}

} // namespace
} // namespace bmfr
