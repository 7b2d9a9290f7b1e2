// The renderer's moving objects: keyframed rigid transforms, exact motion vectors and previous
// positions, checked against the keys by hand; scene-description errors for animations.
#include "io/sequence.h"
#include "render/animation.h"
#include "render/sequence_renderer.h"
#include "temporal/reprojection.h"
#include "test_support.h"
#include <bmfr/error.h>
#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace bmfr::render {
namespace {

TEST(RenderMotion, KeyedTransformsInterpolateAsWrittenByHand) {
    ObjectAnimation a;
    a.pivot = {1, 0, 0};
    RigidKey k0, k1;
    k0.frame = 0, k1.frame = 10;
    k1.translation = {0, 2, 0};
    k1.rotation = quatFromEulerDegrees({0, 90, 0});
    k1.scale = {2, 2, 2};
    a.keys = {k0, k1};
    // Frame 5: half way. Translation (0, 1, 0), 45 degrees about +y through the pivot, scale 1.5.
    const Mat4 m = a.at(5);
    const Vec3 p{2, 0, 0}; // one unit from the pivot along +x
    const Vec4 q = transformPoint(m, p);
    const double r = 1.5, c = std::cos(3.14159265358979 / 4);
    // +x turned 45 degrees about +y goes to (cos, 0, -sin).
    EXPECT_NEAR(q.x, 1 + r * c, 1e-5);
    EXPECT_NEAR(q.y, 1.0, 1e-5);
    EXPECT_NEAR(q.z, -r * c, 1e-5);
    // Held before the first key and after the last.
    EXPECT_NEAR(transformPoint(a.at(-3), p).x, 2.0, 1e-6);
    EXPECT_NEAR(transformPoint(a.at(20), p).y, 2.0, 1e-5);
}

struct Rendered {
    std::vector<FrameData> frames;
};

Rendered renderPreset(const std::string& preset, int w, int h, int n) {
    SceneDescription d = loadSceneDescription(preset, ".");
    d.width = w, d.height = h, d.frames = n, d.referenceSpp = 0;
    const std::string dir = testing::freshDir("RenderMotion", preset).string();
    SequenceRenderOptions o;
    o.output = dir, o.quiet = true;
    renderSequence(
        d, o, nullptr, [](int, int) {}, [](const std::string&) {});
    auto reader = SequenceReader::open(dir);
    Rendered r;
    r.frames.resize(size_t(n));
    for (int i = 0; i < n; ++i) reader->load(i, r.frames[size_t(i)]);
    return r;
}

TEST(RenderMotion, ObjectsCarryTheirPointsAndTheVectorsFindThemInThePreviousFrame) {
    const int w = 96, h = 72;
    const Rendered r = renderPreset("cornell-objects-moving", w, h, 2);
    const FrameData &was = r.frames[0], &now = r.frames[1];
    ASSERT_EQ(now.motion.channels, 2);
    ASSERT_EQ(now.previousPosition.channels, 3);
    // The preset's keys by hand, from frame 1 back to frame 0: the sphere's translation goes
    // from a quarter of the way to its frame-4 key (0, -0.087, 0) back to its frame-0 key; the
    // short block's from 1/15 of (-0.6, 0, 0) back to 0; the tall block turns back by 60/30
    // degrees about its pivot (-0.34, 0, -0.28).
    const Vec3 sphereBack{0.0f, 0.087f / 4.0f, 0.0f}, blockBack{0.6f / 15.0f, 0.0f, 0.0f};
    const double turn = -2.0 * 3.14159265358979 / 180.0;
    int sphere = 0, shortBlock = 0, tallBlock = 0, staticPixels = 0, found = 0;
    for (int y = 1; y < h - 1; ++y)
        for (int x = 1; x < w - 1; ++x) {
            const long i = long(y) * w + x;
            const Vec3 p = load3(now.position.data(), i), pp = load3(now.previousPosition.data(), i);
            const float material = now.extras[0].data()[i];
            Vec3 expected = p;
            // Material ids: 0 white (room and blocks), 4 the sphere. Which white: by place (the
            // short block lies in z > 0, the tall block above it or at z < 0.1).
            const bool white = material == 0.0f;
            const bool room = p.y < 5e-5f || p.y > 1.9999f || p.z < -0.9999f;
            if (material == 4.0f) {
                expected = p + sphereBack, ++sphere;
            } else if (white && !room && p.y < 0.599f && p.z > 0.13f) {
                expected = p + blockBack, ++shortBlock;
            } else if (white && !room && p.y > 0.61f) {
                const double dx = p.x + 0.34, dz = p.z + 0.28, c = std::cos(turn),
                             s = std::sin(turn);
                expected = {float(-0.34 + c * dx + s * dz), p.y, float(-0.28 - s * dx + c * dz)};
                ++tallBlock;
            } else if (white && !room) {
                continue; // where the two blocks are near, place does not tell them apart
            } else {
                ++staticPixels;
            }
            ASSERT_LT(length(pp - expected), 2e-5f)
                << x << "," << y << " material " << material << " p " << p.x << "," << p.y << ","
                << p.z << " was " << pp.x << "," << pp.y << "," << pp.z;
            // Where the vector points, the previous frame saw this point (smooth interiors).
            const Vec2 prev{float(x) + now.motion.data()[2 * i],
                            float(y) + now.motion.data()[2 * i + 1]};
            const BilinearFootprint fp = bilinearFootprint(prev);
            if (fp.x0 < 0 || fp.y0 < 0 || fp.x0 + 1 >= w || fp.y0 + 1 >= h) continue;
            Vec3 seen{}, taps[4];
            float spread = 0;
            for (int t = 0; t < 4; ++t) {
                const long j = long(tapY(fp, t)) * w + tapX(fp, t);
                taps[t] = load3(was.position.data(), j);
                seen += fp.weight[t] * taps[t];
                if (was.extras[0].data()[j] != material) spread = 1e9f;
                if (dot(load3(was.normal.data(), j), load3(now.previousNormal.data(), i)) < 0.999f)
                    spread = 1e9f;
            }
            for (int t = 1; t < 4; ++t) spread = std::max(spread, length(taps[t] - taps[0]));
            // Positions are not linear in screen space under perspective: a grazing wall's
            // taps lie far apart, and the bilinear mean errs by a part of their spread.
            if (spread > 0.08f) continue;
            if (!(length(seen - pp) < 1e-3f + 0.1f * spread)) {
                ADD_FAILURE() << "pixel " << x << "," << y << ": the previous frame saw "
                              << length(seen - pp) << " m away at the vector's end";
                return;
            }
            ++found;
        }
    EXPECT_GT(sphere, 40);
    EXPECT_GT(shortBlock, 100);
    EXPECT_GT(tallBlock, 100);
    EXPECT_GT(staticPixels, 1000);
    EXPECT_GT(found, 2000);
}

TEST(RenderMotion, AnAnimationOfAnUnknownObjectOrBadKeysIsAClearError) {
    auto parse = [](const char* animations) {
        const std::string text =
            std::string(R"({"mesh": "builtin:cornell-objects", "camera": {"keyframes": [)"
                        R"({"position": [0, 1, 3], "target": [0, 1, 0]}]}, "animations": )") +
            animations + "}";
        return parseSceneDescription(nlohmann::json::parse(text), ".");
    };
    auto errorOf = [&](const char* animations) {
        return testing::errorOf([&] {
            SceneDescription d = parse(animations);
            Scene s = loadScene(d.mesh);
            SceneAnimator a(s, d.animations);
        });
    };
    EXPECT_NE(errorOf(R"([{"object": "teapot", "keys": [{"frame": 0}]}])")
                  .find("no such object (objects: light, room, short_block, sphere, tall_block)"),
              std::string::npos);
    EXPECT_NE(errorOf(R"([{"object": "sphere", "keys": []}])").find("\"keys\" is empty"),
              std::string::npos);
    EXPECT_NE(errorOf(R"([{"object": "sphere", "keys": [{"frame": 0, "scale": 0}]}])")
                  .find("scale must be in (0, 1000]"),
              std::string::npos);
    EXPECT_NE(errorOf(R"([{"object": "sphere", "keys": [{"frame": 0}, {"frame": 0}]}])")
                  .find("two keys at frame 0"),
              std::string::npos);
    EXPECT_NE(errorOf(R"([{"object": "sphere", "keys": [{"frame": 0, "spin": 1}]}])").find("spin"),
              std::string::npos);
}

} // namespace
} // namespace bmfr::render
