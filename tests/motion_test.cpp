// Motion-vector reprojection: exact vectors on a procedural scene whose sphere slides and whose
// box turns, moving surfaces keeping their history through them, uncovered points rejected,
// the camera path unchanged without them, cuts, and bad motion input.
#include "synth/procedural_scene.h"
#include "temporal/reprojection.h"
#include "test_support.h"
#include <bmfr/bmfr.hpp>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

constexpr int kSphere = 7, kBox = 8; // the procedural scene's material ids

std::vector<FrameData> movingFrames(int w, int h, int n, float objectSpeed, float cameraSpeed,
                                    bool jitter = true) {
    ProceduralSceneOptions o;
    o.width = w, o.height = h, o.frames = n;
    o.objectSpeed = objectSpeed, o.cameraSpeed = cameraSpeed, o.jitter = jitter;
    o.motionVectors = true;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) scene.render(i, frames[size_t(i)]);
    return frames;
}

int materialAt(const FrameData& f, int x, int y) {
    return int(f.extras[0].data()[long(y) * f.color.width + x]);
}

/// True when the 2x2 taps of `pixel` in `f` all lie in the image on material `m`.
bool footprintOn(const FrameData& f, Vec2 pixel, int m) {
    const BilinearFootprint fp = bilinearFootprint(pixel);
    for (int t = 0; t < 4; ++t) {
        const int x = tapX(fp, t), y = tapY(fp, t);
        if (x < 0 || y < 0 || x >= f.color.width || y >= f.color.height) return false;
        if (materialAt(f, x, y) != m) return false;
    }
    return true;
}

/// True when the 2x2 taps of `pixel` in `f` all face along `n` (one face of the box).
bool footprintFaces(const FrameData& f, Vec2 pixel, Vec3 n) {
    const BilinearFootprint fp = bilinearFootprint(pixel);
    for (int t = 0; t < 4; ++t)
        if (dot(load3(f.normal.data(), long(tapY(fp, t)) * f.color.width + tapX(fp, t)), n) <
            0.999f)
            return false;
    return true;
}

/// The previous frame's position buffer, interpolated bilinearly at `pixel`, and how far apart
/// its taps lie (bilinear interpolation of a curved surface errs by a fraction of that).
Vec3 positionAt(const FrameData& f, Vec2 pixel, float& spread) {
    const BilinearFootprint fp = bilinearFootprint(pixel);
    Vec3 sum{}, tap[4];
    for (int t = 0; t < 4; ++t) {
        tap[t] = load3(f.position.data(), long(tapY(fp, t)) * f.color.width + tapX(fp, t));
        sum += fp.weight[t] * tap[t];
    }
    spread = 0;
    for (int t = 1; t < 4; ++t) spread = std::max(spread, length(tap[t] - tap[0]));
    return sum;
}

TEST(MotionVectors, ProceduralMovingObjectsMatchHandComputedPositions) {
    const int w = 160, h = 120;
    // Both the camera and the objects move, with jitter: the vectors carry all three.
    const std::vector<FrameData> frames = movingFrames(w, h, 3, 1.0f, 1.0f);
    const FrameData &was = frames[1], &now = frames[2];
    int sphere = 0, box = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const long i = long(y) * w + x;
            const int m = materialAt(now, x, y);
            const Vec3 p = load3(now.position.data(), i), n = load3(now.normal.data(), i);
            const Vec3 pp = load3(now.previousPosition.data(), i);
            const Vec3 pn = load3(now.previousNormal.data(), i);
            // The scene's motion by hand: the sphere slides 0.05 m along x per frame; the box
            // turns 0.04 rad per frame about the vertical through its centre (-1.5, 0.8, -1.1).
            double ex = p.x, ey = p.y, ez = p.z, nx = n.x, nz = n.z;
            if (m == kSphere) {
                ex -= 0.05;
            } else if (m == kBox) {
                const double c = std::cos(-0.04), s = std::sin(-0.04);
                const double dx = p.x + 1.5, dz = p.z + 1.1;
                ex = -1.5 + c * dx + s * dz, ez = -1.1 - s * dx + c * dz;
                nx = c * n.x + s * n.z, nz = -s * n.x + c * n.z;
            }
            ASSERT_NEAR(pp.x, ex, 1e-5) << x << "," << y;
            ASSERT_NEAR(pp.y, ey, 1e-5);
            ASSERT_NEAR(pp.z, ez, 1e-5);
            ASSERT_NEAR(pn.x, nx, 1e-5);
            ASSERT_NEAR(pn.z, nz, 1e-5);
            // The vector leads to where the previous frame saw that very point.
            const Vec2 prev{float(x) + now.motion.data()[2 * i],
                            float(y) + now.motion.data()[2 * i + 1]};
            if ((m != kSphere && m != kBox) || !footprintOn(was, prev, m)) continue;
            if (m == kBox && !footprintFaces(was, prev, pn)) continue;
            float spread;
            const Vec3 seen = positionAt(was, prev, spread);
            if (spread > 0.1f) continue; // grazing: a pixel spans too much of the surface
            EXPECT_LT(length(seen - pp), 0.002f + 0.05f * spread)
                << "pixel " << x << "," << y << " material " << m;
            (m == kSphere ? sphere : box)++;
        }
    EXPECT_GT(sphere, 500);
    EXPECT_GT(box, 300);
}

/// BMFR's debug buffers of the last of `frames`, with or without the motion input.
struct LastFrame {
    std::vector<float> historyLength, discardMask;
};
LastFrame runFilter(const std::string& filter, const std::vector<FrameData>& frames, bool motion) {
    auto f = makeFilter(filter, {});
    f->setDebugOutputs(true);
    for (const FrameData& d : frames) f->denoise(d.input(motion));
    const DebugBuffers db = f->debug();
    const size_t n = size_t(db.historyLength.width) * size_t(db.historyLength.height);
    return {std::vector<float>(db.historyLength.data, db.historyLength.data + n),
            std::vector<float>(db.discardMask.data, db.discardMask.data + n)};
}

TEST(MotionVectors, MovingSurfacesKeepTheirHistoryAndUncoveredPointsAreRejected) {
    const int w = 160, h = 120, n = 6;
    // The sphere slides 0.2 m a frame: beyond the 0.1 m position limit of the camera path.
    const std::vector<FrameData> frames = movingFrames(w, h, n, 4.0f, 0.0f);
    const FrameData &was = frames[n - 2], &now = frames[n - 1];
    for (const char* filter : {"bmfr", "svgf"}) {
        const LastFrame with = runFilter(filter, frames, true);
        const LastFrame without = runFilter(filter, frames, false);
        int moving = 0, kept = 0, uncovered = 0, rejected = 0, wrong = 0, lost = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const long i = long(y) * w + x;
                const Vec2 prev{float(x) + now.motion.data()[2 * i],
                                float(y) + now.motion.data()[2 * i + 1]};
                if (materialAt(now, x, y) == kSphere && footprintOn(was, prev, kSphere)) {
                    ++moving;
                    kept += with.historyLength[size_t(i)] >= float(n - 1);
                    wrong += without.historyLength[size_t(i)] > 1.0f;
                    lost += without.historyLength[size_t(i)] == 1.0f;
                }
                // A wall point the sphere covered in the previous frame, wherever it looked.
                if (materialAt(now, x, y) != kSphere && materialAt(now, x, y) != kBox &&
                    footprintOn(was, prev, kSphere)) {
                    ++uncovered;
                    rejected += with.discardMask[size_t(i)] == 0.0f &&
                                with.historyLength[size_t(i)] == 1.0f;
                }
            }
        SCOPED_TRACE(filter);
        ASSERT_GT(moving, 400);
        ASSERT_GT(uncovered, 40) << moving;
        EXPECT_GE(kept, moving * 97 / 100) << "of " << moving << " pixels on the sliding sphere";
        // The camera path alone either loses the history or takes another point's (ghosting).
        EXPECT_GT(lost, moving / 4);
        EXPECT_GT(wrong, moving / 10);
        EXPECT_EQ(rejected, uncovered);
    }
}

TEST(MotionVectors, WithoutThemTheCameraPathGivesTheSameBits) {
    // Motion vectors that describe a static scene exactly as the camera does lead to the same
    // previous pixels; leaving them out must reproduce the camera path's output bit for bit.
    const int w = 64, h = 48, n = 5;
    const std::vector<FrameData> frames = movingFrames(w, h, n, 0.0f, 1.0f);
    for (const char* filter : {"bmfr", "svgf"}) {
        auto a = makeFilter(filter, {}), b = makeFilter(filter, {});
        for (const FrameData& f : frames) {
            FrameInput camera = f.input(false);
            FrameInput worldOnly = f.input(true);
            worldOnly.motion = {}; // previous position = position: projected like the camera
            const ImageView oa = a->denoise(camera), ob = b->denoise(worldOnly);
            ASSERT_EQ(0, std::memcmp(oa.data, ob.data, sizeof(float) * 3 * size_t(w * h)))
                << filter;
        }
    }
}

TEST(MotionVectors, AResetDropsTheHistoryAtThatFrame) {
    std::vector<FrameData> frames = movingFrames(48, 32, 6, 1.0f, 1.0f);
    frames[4].reset = true;
    const std::string dir = testing::freshDir("Motion", "reset").string();
    SequenceInfo info;
    info.width = 48, info.height = 32, info.frameCount = 6, info.extraNames = {"material_id"};
    {
        ManifestWriter writer(dir, info, false);
        for (int i = 0; i < 6; ++i) writer.addFrame(i, frames[size_t(i)]);
    }
    auto reader = SequenceReader::open(dir);
    auto f = makeFilter("bmfr", {});
    f->setDebugOutputs(true);
    for (int i = 0; i < 6; ++i) {
        FrameData d;
        reader->load(i, d);
        EXPECT_EQ(d.reset, i == 4) << i;
        ASSERT_EQ(d.motion.channels, 2);
        ASSERT_EQ(0, std::memcmp(d.motion.data(), frames[size_t(i)].motion.data(),
                                 sizeof(float) * d.motion.pixels.size()));
        f->denoise(d.input());
        const DebugBuffers db = f->debug();
        float longest = 0;
        for (long p = 0; p < 48 * 32; ++p) longest = std::max(longest, db.historyLength.data[p]);
        EXPECT_EQ(longest, i == 4 ? 1.0f : float(i < 4 ? i + 1 : i - 3)) << "frame " << i;
    }
}

TEST(MotionVectors, BadMotionInputIsAClearErrorOrCounted) {
    std::vector<FrameData> frames = movingFrames(24, 16, 2, 1.0f, 1.0f);
    auto f = makeFilter("bmfr", {});
    FrameInput in = frames[0].input();
    ImageF one(24, 16, 1);
    in.motion = view(one);
    EXPECT_NE(testing::errorOf([&] {
                  f->denoise(in);
              }).find("input buffer 'motion' has 1 channels, expected 2 to 4"),
              std::string::npos);
    ImageF small(12, 16, 3);
    in = frames[0].input();
    in.previousPosition = view(small);
    EXPECT_NE(testing::errorOf([&] {
                  f->denoise(in);
              }).find("input buffer 'previousPosition' is 12x16, colour is 24x16"),
              std::string::npos);
    // Non-finite vectors are counted and mean no history there, never a wild read.
    f->denoise(frames[0].input());
    frames[1].motion.data()[0] = NAN;
    frames[1].motion.data()[3] = INFINITY;
    frames[1].motion.data()[5] = 3e9f;
    f->denoise(frames[1].input());
    EXPECT_EQ(f->lastStats().nonFiniteInputs, 2);
}

} // namespace
} // namespace bmfr
