// The key light's visibility as a BMFR feature (BmfrSettings::visibilityFeature): a hard shadow
// edge across blocks fitted exactly against the analytic image, the renderer's sun visibility
// against a hand-computed shadow, and the input errors.
#include "filters/bmfr/visibility_taps.h"
#include "io/sequence.h"
#include "render/sequence_renderer.h"
#include "test_scenes.h"
#include "test_support.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;

constexpr int kVisW = 64, kVisH = 48;

/// The sun's visibility times its cosine: a diagonal hard edge.
float visibilityAt(int x, int y, int edge = 40) {
    return float(x) + 0.6f * float(y) < float(edge) ? 0.8f : 0.0f;
}

/// A fronto-parallel plane whose demodulated radiance is 0.4 + 2 visibility + 0.05 p.x (positive:
/// p.x is within 6.7 of 0), and albedo 0.5: exactly in the span of the paper's features and the
/// visibility.
FrameData shadowFrame(int edge = 40) {
    const Mat4 vp = test::cameraAt({0, 0, 0}, kVisW, kVisH);
    FrameData f = test::planeFrame(vp, kVisW, kVisH, {0, 0, 0}, [](int, int) { return -5.0f; });
    f.visibility = ImageF(kVisW, kVisH, 1);
    for (int y = 0; y < kVisH; ++y)
        for (int x = 0; x < kVisW; ++x) {
            const long i = long(y) * kVisW + x;
            const float v = visibilityAt(x, y, edge), px = f.position.data()[3 * i];
            const float radiance = 0.4f + 2.0f * v + 0.05f * px;
            store3(f.albedo.data(), i, {0.5f, 0.5f, 0.5f});
            store3(f.color.data(), i, {0.5f * radiance, 0.4f * radiance, 0.3f * radiance});
            f.visibility.data()[i] = v;
        }
    return f;
}

/// The worst absolute error of the third frame against the exact image.
double worstError(const std::string& backend, bool visibility) {
    const FrameData frame = shadowFrame();
    auto filter = makeFilter("bmfr", {{"backend", backend},
                                      {"taa", "false"},
                                      {"noiseAmplitude", "0"},
                                      {"halfHistory", "false"},
                                      {"visibilityFeature", visibility ? "true" : "false"}});
    ImageView out;
    for (int i = 0; i < 3; ++i) out = filter->denoise(frame.input());
    double worst = 0.0;
    for (long k = 0; k < long(kVisW) * kVisH * 3; ++k)
        worst = std::max(worst, std::fabs(double(out.data[k]) - frame.color.data()[k]));
    return worst;
}

TEST(VisibilityFeature, AHardShadowEdgeIsFittedExactly) {
    for (const char* backend : {"reference", "cpu"}) {
        // The paper's features cannot bend along the edge: the blocks it crosses smear it.
        EXPECT_GT(worstError(backend, false), 0.1) << backend;
        EXPECT_LT(worstError(backend, true), 2e-3) << backend;
    }
}

TEST(VisibilityFeature, OffOrWithoutTheBufferTheFitIsThePapers) {
    // The switch with frames that have no visibility is the same bits as the switch off.
    FrameData frame = shadowFrame();
    const FrameData plain = [&] {
        FrameData f = frame;
        f.visibility = ImageF();
        return f;
    }();
    auto on = makeFilter("bmfr", {{"visibilityFeature", "true"}});
    auto off = makeFilter("bmfr", {{"visibilityFeature", "false"}, {"visibilityTaps", "false"}});
    for (int i = 0; i < 2; ++i) {
        const ImageView a = on->denoise(plain.input()), b = off->denoise(frame.input());
        for (long k = 0; k < long(kVisW) * kVisH * 3; ++k) ASSERT_EQ(a.data[k], b.data[k]) << k;
    }
}

TEST(VisibilityFeature, ItComesWithEveryFrameOrNoneAndIsChecked) {
    const FrameData frame = shadowFrame();
    FrameData without = frame;
    without.visibility = ImageF();
    auto filter = makeFilter("bmfr", {{"visibilityFeature", "true"}});
    filter->denoise(frame.input());
    EXPECT_NE(testing::errorOf([&] {
                  filter->denoise(without.input());
              }).find("this frame lacks a visibility buffer and the earlier frames had one"),
              std::string::npos);
    // After a cut the feature set may change.
    without.reset = true;
    EXPECT_EQ(testing::errorOf([&] { filter->denoise(without.input()); }), "(no error)");

    FrameData small = frame;
    small.visibility = ImageF(kVisW / 2, kVisH, 1);
    EXPECT_NE(testing::errorOf([&] { filter->denoise(small.input()); }).find("visibility"),
              std::string::npos);
    // A non-finite visibility is counted and read as 0.
    FrameData bad = frame;
    bad.visibility.data()[5] = std::nanf("");
    filter->reset();
    const ImageView out = filter->denoise(bad.input());
    EXPECT_EQ(filter->lastStats().nonFiniteInputs, 1);
    for (long k = 0; k < long(kVisW) * kVisH * 3; ++k) ASSERT_TRUE(std::isfinite(out.data[k]));
    // 24 feature columns and the visibility do not fit.
    EXPECT_NE(testing::errorOf([] {
                  makeFilter("bmfr", {{"visibilityFeature", "true"},
                                      {"features", "1,n.x,n.y,n.z,p.x,p.y,p.z,p.x^2,p.y^2,p.z^2,"
                                                   "p.x^3,p.y^3,p.z^3,p.x^4,p.y^4,p.z^4,n.x^2,"
                                                   "n.y^2,n.z^2,n.x^3,n.y^3,n.z^3,p.x^5,p.y^5"}});
              }).find("and the visibility"),
              std::string::npos);
}

TEST(VisibilityFeature, TheRendererWritesTheSunsShadowByHand) {
    // A floor (y = 0, x and z in [-2, 2]) under a slab (y = 1, x in [-0.5, 0.5]); the sun
    // along (1, 1, 0) throws the slab's shadow onto x in [-1.5, -0.5]. Seen from above.
    const fs::path d = testing::freshDir("visibility", "render");
    std::ofstream(d / "m.obj") << "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\n"
                                  "v -0.5 1 -2\nv 0.5 1 -2\nv 0.5 1 2\nv -0.5 1 2\n"
                                  "f 1 3 2\nf 1 4 3\nf 5 7 6\nf 5 8 7\n";
    std::ofstream(d / "s.json") << R"({"mesh": "m.obj", "width": 48, "height": 32, "frames": 1,
        "reference_spp": 0, "jitter": false,
        "sun": {"direction": [1, 1, 0], "angular_diameter_deg": 0.53, "irradiance": [3, 3, 3]},
        "camera": {"keyframes": [{"position": [0, 6, 0.01], "target": [0, 0, 0]}]}})";
    render::SceneDescription desc =
        render::loadSceneDescription((d / "s.json").string(), d.string());
    render::renderSequence(
        desc, {(d / "out").string()}, nullptr, [](int, int) {}, [](const std::string&) {});
    FrameData f;
    SequenceReader::open((d / "out").string())->load(0, f);
    ASSERT_EQ(f.visibility.width, 48);
    const float lit = 1.0f / std::sqrt(2.0f);
    int shadowed = 0, sunlit = 0;
    for (long i = 0; i < 48L * 32; ++i) {
        const float* p = f.position.data() + 3 * i;
        const float v = f.visibility.data()[i];
        if (std::fabs(p[0]) > 1.95f || std::fabs(p[2]) > 1.95f) continue; // edges and sky
        if (std::fabs(p[1] - 1.0f) < 1e-3f) {                             // the slab's top
            EXPECT_NEAR(v, lit, 1e-4f) << i;
            continue;
        }
        ASSERT_NEAR(p[1], 0.0f, 1e-3f) << i;
        if (std::fabs(p[0] + 1.5f) < 0.05f || std::fabs(p[0] + 0.5f) < 0.05f) continue;
        const bool inShadow = p[0] > -1.5f && p[0] < -0.5f;
        EXPECT_NEAR(v, inShadow ? 0.0f : lit, 1e-4f) << p[0] << " " << p[2];
        (inShadow ? shadowed : sunlit) += 1;
    }
    EXPECT_GT(shadowed, 50);
    EXPECT_GT(sunlit, 50);
    fs::remove_all(d);
}

TEST(VisibilityTaps, HistoryTapsOfTheOtherLitClassAreDropped) {
    // A pixel that came from (1.5, 0.5): taps (1,0), (2,0), (1,1), (2,1) of a 4-wide image;
    // (2, 0) was in the sun last frame.
    std::vector<uint8_t> prevLit(8, 0), lit(8, 9);
    prevLit[2] = 1;
    const float shadowed[8] = {}, sunlit[8] = {0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f, 0.5f};
    EXPECT_EQ(sameLitTaps(0b1111, {1.5f, 0.5f}, shadowed, prevLit.data(), lit.data(), 5, 4),
              0b1101);
    EXPECT_EQ(lit[5], 0);
    EXPECT_EQ(sameLitTaps(0b1111, {1.5f, 0.5f}, sunlit, prevLit.data(), lit.data(), 5, 4), 0b0010);
    EXPECT_EQ(lit[5], 1);
    // Without history every tap stays, and the class is still recorded; NaN is in shadow.
    const float nan[8] = {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};
    EXPECT_EQ(sameLitTaps(0b1111, {1.5f, 0.5f}, nan, nullptr, lit.data(), 5, 4), 0b1111);
    EXPECT_EQ(lit[5], 0);
}

/// The worst error, against the exact image, in the band a moving shadow edge swept: frames
/// with the edge at 40, then one with it at 48. With `phaseOne` the noisy accumulation is on
/// (the frames are noise-free, so it is exact where its taps are of the same class).
double sweptBandError(const std::string& backend, bool taps, bool phaseOne = false) {
    const FrameData before = shadowFrame(40), after = shadowFrame(48);
    auto filter = makeFilter("bmfr", {{"backend", backend},
                                      {"noiseAmplitude", "0"},
                                      {"halfHistory", "false"},
                                      {"taaSameSurface", "true"},
                                      // Phase I off: the fit sees this frame alone and is exact.
                                      {"firstAccumulation", phaseOne ? "true" : "false"},
                                      {"visibilityFeature", "true"},
                                      {"visibilityTaps", taps ? "true" : "false"}});
    for (int i = 0; i < 4; ++i) filter->denoise(before.input());
    const ImageView out = filter->denoise(after.input());
    double worst = 0.0;
    for (int y = 0; y < kVisH; ++y)
        for (int x = 0; x < kVisW; ++x) {
            if (visibilityAt(x, y, 40) == visibilityAt(x, y, 48)) continue;
            const long i = 3 * (long(y) * kVisW + x);
            for (int c = 0; c < 3; ++c)
                worst =
                    std::max(worst, std::fabs(double(out.data[i + c]) - after.color.data()[i + c]));
        }
    return worst;
}

TEST(VisibilityTaps, AMovingShadowLeavesNoTrail) {
    // The swept band turned from sunlit to shadowed. Phase III and TAA blend the sunlit
    // history into it unless the taps of the other class are dropped. (Phase I is off here so
    // that the fit is exact; the next test turns it on.)
    for (const char* backend : {"reference", "cpu"}) {
        const double with = sweptBandError(backend, true), without = sweptBandError(backend, false);
        EXPECT_GT(without, 0.3) << backend;
        EXPECT_LT(with, 2e-3) << backend;
    }
}

TEST(VisibilityTaps, PhaseOneKeepsTheSweptBandOutOfTheFit) {
    // With phase I on, its sunlit history would reach the fit's input in the swept band too.
    for (const char* backend : {"reference", "cpu"}) {
        const double with = sweptBandError(backend, true, true),
                     without = sweptBandError(backend, false, true);
        EXPECT_GT(without, 0.3) << backend;
        EXPECT_LT(with, 2e-3) << backend;
    }
}

} // namespace
} // namespace bmfr
