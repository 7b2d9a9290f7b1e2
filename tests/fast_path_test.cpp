// The fast CPU passes against the reference passes: the same sequence through both, every
// frame's output compared, on procedural frames (odd sizes, non-finite input, every stage
// switch, several block sizes) and on path-traced Cornell-box frames.
#include "core/image.h"
#include "render/frame_renderer.h"
#include "render/lights.h"
#include "render/ray_accel.h"
#include "render/scene.h"
#include "synth/procedural_scene.h"
#include <bmfr/denoiser.h>
#include <cmath>
#include <functional>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

// The stated tolerance: |fast - reference| <= kAbs + kRel * |reference| per channel, and the
// mean difference below kMean. Both run the same algorithm; they differ by summation order in
// the QR, fused multiply-adds and one reciprocal per scaled column.
constexpr double kAbs = 1e-4, kRel = 1e-3, kMean = 1e-5;

struct Difference {
    double worstExcess = 0; ///< max of |d| - (kAbs + kRel |ref|); <= 0 passes
    double mean = 0;
    double maxAbs = 0;
};

Difference compareViews(const ImageView& fast, const ImageView& ref) {
    Difference d;
    const long n = long(ref.width) * ref.height * 3;
    for (long i = 0; i < n; ++i) {
        const double r = ref.data[i], f = fast.data[i], e = std::fabs(f - r);
        d.worstExcess = std::max(d.worstExcess, e - (kAbs + kRel * std::fabs(r)));
        d.maxAbs = std::max(d.maxAbs, e);
        d.mean += e;
    }
    d.mean /= double(n);
    return d;
}

using FrameSource = std::function<const FrameInput&(int)>;

void expectSameOutputs(Settings s, int frames, const FrameSource& frame, const char* what) {
    Settings fs = s, rs = s;
    fs.implementation = Implementation::Fast;
    rs.implementation = Implementation::Reference;
    Denoiser fast(fs), ref(rs);
    fast.setDebugOutputs(true), ref.setDebugOutputs(true);
    for (int i = 0; i < frames; ++i) {
        const FrameInput& in = frame(i);
        const ImageView a = fast.denoise(in), b = ref.denoise(in);
        ASSERT_EQ(fast.lastStats().nonFiniteInputs, ref.lastStats().nonFiniteInputs) << what;
        ASSERT_EQ(fast.lastStats().discardedPixels, ref.lastStats().discardedPixels) << what;
        const Difference d = compareViews(a, b);
        EXPECT_LE(d.worstExcess, 0.0) << what << ", frame " << i << ": max |diff| " << d.maxAbs;
        EXPECT_LE(d.mean, kMean) << what << ", frame " << i;
        // Phase I and its discard decisions agree exactly on these inputs.
        const DebugBuffers da = fast.debug(), db = ref.debug();
        for (long p = 0; p < long(in.color.width) * in.color.height; ++p) {
            ASSERT_EQ(da.discardMask.data[p], db.discardMask.data[p]) << what << ", pixel " << p;
            ASSERT_EQ(da.historyLength.data[p], db.historyLength.data[p]) << what;
        }
    }
}

struct ProceduralFrames {
    ProceduralScene scene;
    std::vector<FrameData> frames;
    ProceduralFrames(int w, int h, int n, bool poison) : scene(options(w, h, n)) {
        frames.resize(size_t(n));
        for (int i = 0; i < n; ++i) {
            scene.render(i, frames[size_t(i)]);
            if (poison && i % 3 == 1) {
                frames[size_t(i)].color.pixels[5] = NAN;
                frames[size_t(i)].normal.pixels[3 * 17 + 1] = INFINITY;
                frames[size_t(i)].position.pixels.back() = -INFINITY;
            }
        }
    }
    static ProceduralSceneOptions options(int w, int h, int n) {
        ProceduralSceneOptions o;
        o.width = w, o.height = h, o.frames = n;
        return o;
    }
    FrameSource source() {
        return [this](int i) -> const FrameInput& {
            input = frames[size_t(i)].input();
            return input;
        };
    }
    FrameInput input;
};

TEST(FastPath, MatchesReferenceOnProceduralFramesOfOddSize) {
    ProceduralFrames p(203, 117, 12, true);
    expectSameOutputs(Settings{}, 12, p.source(), "default settings, 203x117, with NaN/Inf");
}

TEST(FastPath, MatchesReferenceOnImagesSmallerThanABlock) {
    // Blocks mirror the image more than once, so most rows are read by rows of blocks that do
    // not own them (accumulated ahead of the rows of blocks, see accumulate_fit.cpp).
    ProceduralFrames tall(9, 70, 6, false), wide(70, 9, 6, false), tiny(5, 3, 6, false);
    expectSameOutputs(Settings{}, 6, tall.source(), "9x70");
    expectSameOutputs(Settings{}, 6, wide.source(), "70x9");
    expectSameOutputs(Settings{}, 6, tiny.source(), "5x3");
}

TEST(FastPath, MatchesReferenceForEveryStageSwitchAndBlockSize) {
    ProceduralFrames p(96, 72, 6, false);
    for (int b : {8, 20, 24, 64}) {
        Settings s;
        s.blockSize = b;
        expectSameOutputs(s, 6, p.source(), ("block size " + std::to_string(b)).c_str());
    }
    const char* names[] = {"no demodulation", "no phase I", "no fitting", "no phase III", "no TAA"};
    for (int k = 0; k < 5; ++k) {
        Settings s;
        bool* flags[] = {&s.stages.demodulate, &s.stages.firstAccumulation, &s.stages.fitting,
                         &s.stages.secondAccumulation, &s.stages.taa};
        *flags[k] = false;
        expectSameOutputs(s, 6, p.source(), names[k]);
    }
    Settings extra;
    extra.features.push_back({FeatureSource::Extra, 0, 1.0f, true});
    expectSameOutputs(extra, 6, p.source(), "an extra feature");
    // Rows of a block that are not a multiple of eight pixels, and exponents other than 1 and 2.
    Settings odd;
    odd.blockSize = 14;
    odd.features = parseFeatures("1,n.x,n.y,n.z,p.x,p.y^3,p.z^0.5,p.x^2,extra0^2");
    expectSameOutputs(odd, 6, p.source(), "block size 14, exponents 3, 0.5 and 2 on an extra");
}

TEST(FastPath, MatchesReferenceOnPathTracedFrames) {
    using namespace render;
    Scene box = builtinCornellBox();
    RayAccel accel(box);
    LightSet lights(box, {}, {});
    const int w = 77, h = 61, n = 8;
    FrameRenderer r(box, accel, w, h, 1, 11);
    std::vector<FrameData> frames(n);
    CameraPose previous;
    for (int i = 0; i < n; ++i) {
        CameraPose pose;
        pose.position = {0.05f * float(i), 1.0f, 3.4f}, pose.target = {0, 1, 0};
        pose.fovY = 0.69f;
        FrameRenderStats stats;
        ASSERT_TRUE(
            r.render(i, pose, previous, i > 0, lights, true, 0, frames[size_t(i)], stats, nullptr));
        previous = pose;
    }
    FrameInput input;
    expectSameOutputs(
        Settings{}, n,
        [&](int i) -> const FrameInput& {
            input = frames[size_t(i)].input();
            return input;
        },
        "path-traced Cornell box, 77x61");
}

} // namespace
} // namespace bmfr
