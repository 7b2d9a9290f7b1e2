// The renderer's moving objects: keyframed rigid transforms, exact motion vectors and previous
// positions, checked against the keys by hand; scene-description errors for animations.
#include "io/sequence.h"
#include "render/animation.h"
#include "render/sequence_renderer.h"
#include "temporal/reprojection.h"
#include "test_support.h"
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>
#include <fstream>
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
    ASSERT_EQ(now.motion.channels, 3); // x, y and the depth offset
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
            const Vec3 p = load3(now.position.data(), i),
                       pp = load3(now.previousPosition.data(), i);
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
            const Vec2 prev{float(x) + now.motion.data()[3 * i],
                            float(y) + now.motion.data()[3 * i + 1]};
            // The depth offset: the point's view depth by the previous camera minus now.
            const float offset =
                transformPoint(was.viewProjection, pp).w - transformPoint(now.viewProjection, p).w;
            ASSERT_NEAR(now.motion.data()[3 * i + 2], offset, 1e-4f * (1 + std::fabs(offset)));
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

/// A glTF file: "mover" (no mesh) slides 1 m along x from 0 to 1 s and carries its child
/// "rider" (a triangle 2 m behind it); "floor" (the same triangle, 1 m down) stays.
std::string writeAnimatedGltf(const std::filesystem::path& dir) {
    const float data[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, // POSITION
                          0, 1,                      // times, seconds
                          0, 0, 0, 1, 0, 0};         // translations
    std::ofstream(dir / "anim.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(data), sizeof data);
    const char* gltf = R"({
      "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 2]}],
      "nodes": [{"name": "mover", "children": [1]},
                {"name": "rider", "mesh": 0, "translation": [0, 0, -2]},
                {"name": "floor", "mesh": 0, "translation": [0, -1, 0]}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
      "buffers": [{"uri": "anim.bin", "byteLength": 68}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                      {"buffer": 0, "byteOffset": 36, "byteLength": 8},
                      {"buffer": 0, "byteOffset": 44, "byteLength": 24}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                     "min": [0, 0, 0], "max": [1, 1, 0]},
                    {"bufferView": 1, "componentType": 5126, "count": 2, "type": "SCALAR",
                     "min": [0], "max": [1]},
                    {"bufferView": 2, "componentType": 5126, "count": 2, "type": "VEC3"}],
      "animations": [{"name": "slide", "channels": [{"sampler": 0, "target": {"node": 0,
                      "path": "translation"}}], "samplers": [{"input": 1, "output": 2}]}]})";
    std::ofstream(dir / "anim.gltf") << gltf;
    return (dir / "anim.gltf").string();
}

TEST(RenderMotion, GltfAnimationChannelsMoveTheirNodesAndChildren) {
    const auto dir = testing::freshDir("RenderMotion", "gltf");
    const Scene rest = loadScene(writeAnimatedGltf(dir));
    ASSERT_EQ(rest.objectNames, (std::vector<std::string>{"rider", "floor"}));
    ASSERT_EQ(rest.nodeChannels.size(), 1u);
    EXPECT_NEAR(rest.positions[1].z, -2.0f, 1e-6f); // the rider at rest, 2 m behind
    const SceneAnimator animator(rest, {}, 10.0f);  // 10 frames a second
    ASSERT_TRUE(animator.animated());
    Scene posed = rest;
    animator.pose(5, posed); // 0.5 s: the mover, and so the rider, 0.5 m along x
    for (int v = 0; v < 3; ++v) {
        EXPECT_NEAR(posed.positions[size_t(v)].x, rest.positions[size_t(v)].x + 0.5f, 1e-6f);
        EXPECT_NEAR(posed.positions[size_t(v)].z, rest.positions[size_t(v)].z, 1e-6f);
        EXPECT_EQ(posed.positions[3 + size_t(v)].x, rest.positions[3 + size_t(v)].x); // floor
    }
    animator.pose(25, posed); // held after the last key
    EXPECT_NEAR(posed.positions[0].x, 1.0f, 1e-6f);
    std::vector<Mat4> points, normals;
    animator.toPrevious(5, points, normals);
    const Vec4 back = transformPoint(points[0], {0.5f, 0, -2});
    EXPECT_NEAR(back.x, 0.4f, 1e-6f);
    EXPECT_NEAR(transformPoint(points[1], {0.3f, -1, 0}).x, 0.3f, 1e-7f); // the floor stays
    // Played from a scene description; a file without animations is refused.
    const std::string text = R"({"mesh": ")" + (dir / "anim.gltf").string() +
                             R"(", "gltf_animation": {"fps": 24}, "sky": {"radiance": [1, 1, 1]},
        "camera": {"keyframes": [{"position": [0, 0, 3], "target": [0, 0, 0]}]}})";
    EXPECT_EQ(parseSceneDescription(nlohmann::json::parse(text), ".").gltfAnimationFps, 24.0f);
    EXPECT_NE(
        testing::errorOf([] { SceneAnimator(builtinCornellBox(), {}, 30.0f); }).find("it has none"),
        std::string::npos);
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
