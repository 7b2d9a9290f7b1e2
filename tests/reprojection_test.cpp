// Reprojection against hand-computed pinhole projection; disocclusion rejection.
#include "temporal/reprojection.h"
#include "test_scenes.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

TEST(Reprojection, KnownCameraMotionMapsToExpectedPreviousPixel) {
    const int W = 640, H = 360;
    const double fovY = 1.0, f = 1.0 / std::tan(fovY / 2), aspect = double(W) / H;
    // Previous camera at (1, 0.5, 2) looking down -z: written out by hand, not by helpers.
    const double ex = 1.0, ey = 0.5, ez = 2.0, n = 0.1, far = 100.0;
    Mat4 vp;
    vp.m[0][0] = float(f / aspect), vp.m[0][3] = float(-f / aspect * ex);
    vp.m[1][1] = float(-f), vp.m[1][3] = float(f * ey);
    vp.m[2][2] = float((far + n) / (n - far));
    vp.m[2][3] = float(-(far + n) / (n - far) * ez + 2 * far * n / (n - far));
    vp.m[3][2] = -1.0f, vp.m[3][3] = float(ez);
    vp.m[3][0] = vp.m[3][1] = 0;
    const float jitter[2] = {0.25f, -0.125f};

    const Vec3 p{0.3f, 1.1f, -3.0f};
    // Camera space: (p - eye), depth d = ez - pz = 5.
    const double cx = 0.3 - ex, cy = 1.1 - ey, depth = ez - (-3.0);
    const double ndcX = f / aspect * cx / depth, ndcY = -f * cy / depth;
    const double expectX = (ndcX * 0.5 + 0.5) * W - 0.5 - 0.25;
    const double expectY = (ndcY * 0.5 + 0.5) * H - 0.5 + 0.125;

    Vec2 got;
    ASSERT_TRUE(projectToPixel(vp, p, jitter, W, H, got));
    EXPECT_NEAR(got.x, expectX, 1e-3);
    EXPECT_NEAR(got.y, expectY, 1e-3);
    // Above the centre in world space means a smaller row index (rows grow downwards).
    EXPECT_LT(got.y, H / 2.0);

    // Behind the camera: no history.
    EXPECT_FALSE(projectToPixel(vp, Vec3{1.0f, 0.5f, 5.0f}, jitter, W, H, got));
}

TEST(Reprojection, BilinearFootprintAndTapTests) {
    BilinearFootprint fp = bilinearFootprint({2.25f, 3.5f});
    EXPECT_EQ(fp.x0, 2);
    EXPECT_EQ(fp.y0, 3);
    EXPECT_FLOAT_EQ(fp.weight[0], 0.75f * 0.5f);
    EXPECT_FLOAT_EQ(fp.weight[1], 0.25f * 0.5f);
    EXPECT_FLOAT_EQ(fp.weight[3], 0.25f * 0.5f);

    // 4x4 previous frame: a wall at z = -5 with normal +z, except pixel (3, 4) region.
    const int w = 4, h = 4;
    std::vector<float> pos(w * h * 3), nrm(w * h * 3);
    for (int i = 0; i < w * h; ++i) {
        store3(pos.data(), i, {float(i % w), float(i / w), -5.0f});
        store3(nrm.data(), i, {0, 0, 1});
    }
    store3(nrm.data(), 1 * w + 2, {1, 0, 0}); // tap (1,0) of the footprint below: normal differs
    store3(pos.data(), 2 * w + 1, {1, 2, -4.0f}); // tap (0,1): one unit in front
    BilinearFootprint f = bilinearFootprint({1.5f, 1.5f});
    uint8_t mask = acceptTaps(f, {1.5f, 1.5f, -5.0f}, {0, 0, 1}, pos.data(), nrm.data(), w, h,
                              DiscardLimits{1.0f, 1.0f});
    // Taps: (1,1) ok, (2,1) normal fails, (1,2) position fails, (2,2) ok.
    EXPECT_EQ(mask, 0b1001);
    // Out of the image: rejected.
    EXPECT_EQ(acceptTaps(bilinearFootprint({3.5f, 3.5f}), {3.5f, 3.5f, -5.0f}, {0, 0, 1},
                         pos.data(), nrm.data(), w, h, DiscardLimits{1.0f, 1.0f}),
              0b0001);
}

/// A wall at z = -10, then an object at z = -5 that covers its left half.
struct LeftHalfCovered {
    int w = 48, h = 32;
    Mat4 cam = test::cameraAt({0, 0, 0}, w, h);
    FrameData background = test::planeFrame(cam, w, h, {1, 1, 1}, [](int, int) { return -10.0f; });
    FrameData occluder = test::planeFrame(
        cam, w, h, {1, 1, 1}, [this](int x, int) { return x < w / 2 ? -5.0f : -10.0f; });
};

TEST(Reprojection, DisoccludedPixelsAreRejectedByTheDenoiser) {
    const LeftHalfCovered scene;
    const int w = scene.w, h = scene.h;
    const FrameData &background = scene.background, &occluder = scene.occluder;
    Settings s;
    s.threads = 2;
    s.positionLimitSquared = 1.0f; // neighbouring pixels lie 0.6 units apart at depth 10
    Denoiser d(s);
    d.setDebugOutputs(true);
    d.denoise(background.input());
    d.denoise(occluder.input());
    DebugBuffers dbg = d.debug();
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float mask = dbg.discardMask.data[y * w + x];
            float len = dbg.historyLength.data[y * w + x];
            if (x < w / 2) {
                EXPECT_EQ(mask, 0) << x << "," << y;
                EXPECT_EQ(len, 1) << x << "," << y;
            } else if (x > w / 2 && x < w - 1 && y > 0 && y < h - 1) {
                EXPECT_EQ(mask, 15) << x << "," << y;
                EXPECT_EQ(len, 2) << x << "," << y;
            }
        }
    EXPECT_EQ(d.lastStats().discardedPixels, long(w / 2) * h);
}

/// FrameStats::discardedPixels counts the same pixels for every filter: those that had a
/// history and kept none of it.
class FrameStatsOfEveryFilter : public ::testing::TestWithParam<std::string> {};

TEST_P(FrameStatsOfEveryFilter, CountTheDisoccludedHalfForEveryFilter) {
    const LeftHalfCovered scene;
    const int w = scene.w, h = scene.h;
    const FrameData &background = scene.background, &occluder = scene.occluder;
    for (const char* backend : {"reference", "cpu"}) {
        std::unique_ptr<Filter> f = makeFilter(
            GetParam(), {{"positionLimitSquared", "1"}, {"threads", "2"}, {"backend", backend}});
        f->denoise(background.input());
        EXPECT_EQ(f->lastStats().discardedPixels, 0) << backend << ": no history yet";
        f->denoise(occluder.input());
        EXPECT_EQ(f->lastStats().discardedPixels, long(w / 2) * h) << backend;
        f->denoise(occluder.input());
        EXPECT_EQ(f->lastStats().discardedPixels, 0) << backend << ": a still frame";
        f->reset();
        f->denoise(occluder.input());
        EXPECT_EQ(f->lastStats().discardedPixels, 0) << backend << ": after a reset";
    }
}

/// FrameStats::nonFiniteInputs counts the same values for every filter: each NaN or Inf of the
/// buffers the filter reads, once.
TEST_P(FrameStatsOfEveryFilter, NonFiniteInputsCountEachBadValueOnceForEveryFilter) {
    const int w = 40, h = 24;
    const Mat4 cam = test::cameraAt({0, 0, 0}, w, h);
    FrameData frame = test::planeFrame(cam, w, h, {1, 1, 1}, [](int, int) { return -10.0f; });
    frame.color.data()[5] = NAN;
    frame.color.data()[3 * 100 + 1] = INFINITY;
    frame.albedo.data()[3 * 200] = -INFINITY;
    for (const char* backend : {"reference", "cpu"}) {
        std::unique_ptr<Filter> f = makeFilter(GetParam(), {{"backend", backend}});
        f->denoise(frame.input());
        EXPECT_EQ(f->lastStats().nonFiniteInputs, 3) << backend;
        EXPECT_GT(f->lastStats().times.count, 0) << backend;
        EXPECT_GT(f->lastStats().times.total, 0.0) << backend;
    }
}

INSTANTIATE_TEST_SUITE_P(EveryFilter, FrameStatsOfEveryFilter, ::testing::ValuesIn(filterNames()),
                         [](const auto& p) { return p.param; });

} // namespace
} // namespace bmfr
