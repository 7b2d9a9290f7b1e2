// Scene loading (glTF, OBJ, built-in), scene descriptions and presets, clear errors, resume.
#include "io/sequence.h"
#include "render/ray_accel.h"
#include "render/sequence_renderer.h"
#include "test_support.h"
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

namespace bmfr::render {
namespace {

namespace fs = std::filesystem;

// Tests run from build/tests; the shared scenes sit beside the checkout.
fs::path scenesDir() {
    for (fs::path p :
         {fs::path(BMFR_SOURCE_DIR) / ".." / "shared" / "scenes", fs::path("../shared/scenes")})
        if (fs::exists(p / "sponza")) return p;
    return {};
}

void expectError(const std::function<void()>& f, const std::string& needle) {
    try {
        f();
        ADD_FAILURE() << "no error, expected: " << needle;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
}

TEST(RenderScene, SponzaGltfLoadsWithTexturesAlphaMasksAndCameras) {
    fs::path dir = scenesDir();
    if (dir.empty()) GTEST_SKIP() << "../shared/scenes not found";
    Scene s = loadScene((dir / "sponza" / "Sponza.gltf").string());
    EXPECT_GT(s.triangleCount(), 250000u);
    EXPECT_EQ(s.cameras.size(), 4u);
    EXPECT_EQ(s.cameras[0].name, "CameraMain");
    int masked = 0, textured = 0;
    for (const Material& m : s.materials)
        masked += m.alphaMask, textured += m.baseColorTexture >= 0;
    EXPECT_GE(masked, 2);
    EXPECT_GE(textured, 20);
    for (const std::string& w : s.warnings)
        EXPECT_EQ(w.find("missing texture"), std::string::npos) << w;
}

TEST(RenderScene, CornellObjLoadsItsLight) {
    fs::path dir = scenesDir();
    if (dir.empty()) GTEST_SKIP() << "../shared/scenes not found";
    Scene s = loadScene((dir / "cornellbox" / "CornellBox-Original.obj").string());
    EXPECT_GT(s.triangleCount(), 20u);
    bool light = false;
    for (const Material& m : s.materials)
        if (m.name == "light")
            light = m.emission.x == 17 && m.emission.y == 12 && m.emission.z == 4;
    EXPECT_TRUE(light);
}

TEST(RenderScene, MissingTextureIsAWarningAndAFlatColour) {
    fs::path d = testing::freshDir("render", "missing_tex");
    std::ofstream(d / "m.mtl") << "newmtl wall\nKd 0.5 0.4 0.3\nmap_Kd does_not_exist.png\n";
    std::ofstream(d / "m.obj") << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl wall\nf 1 2 3\n";
    Scene s = loadScene((d / "m.obj").string());
    ASSERT_EQ(s.warnings.size(), 1u);
    EXPECT_NE(s.warnings[0].find("missing texture"), std::string::npos);
    EXPECT_EQ(s.materials[0].baseColorTexture, -1);
    EXPECT_FLOAT_EQ(s.materials[0].baseColor.y, 0.4f);
    fs::remove_all(d);
}

TEST(RenderScene, UnsupportedGltfFeatureAndBadFilesAreClearErrors) {
    fs::path d = testing::freshDir("render", "gltf");
    std::ofstream(d / "draco.gltf") << R"({"asset": {"version": "2.0"},
        "extensionsUsed": ["KHR_draco_mesh_compression"],
        "extensionsRequired": ["KHR_draco_mesh_compression"], "scenes": [{"nodes": []}]})";
    expectError([&] { loadScene((d / "draco.gltf").string()); },
                "unsupported glTF feature in " + (d / "draco.gltf").string() +
                    ": required extension KHR_draco_mesh_compression");
    expectError([&] { loadScene((d / "nothing.gltf").string()); }, "scene file not found");
    std::ofstream(d / "x.ply") << "ply";
    expectError([&] { loadScene((d / "x.ply").string()); }, "unsupported scene format");
    fs::remove_all(d);
}

TEST(RenderScene, PresetsParseAndAnUnknownNameListsThem) {
    for (const std::string& name : presetNames()) {
        SceneDescription d = loadSceneDescription(name, "/scenes", false);
        EXPECT_FALSE(d.cameraKeys.empty()) << name;
        // The rooms are small measuring sequences (scripts/quality-tables.sh); the others are
        // the paper's references.
        const bool room = name.rfind("room-", 0) == 0;
        EXPECT_EQ(d.referenceSpp, room ? 64 : 4096) << name;
    }
    EXPECT_EQ(presetNames().size(), 10u);
    // The Sponza presets open the atrium's roof and sample the sun and sky apart.
    const SceneDescription atrium = loadSceneDescription("sponza-atrium", "/s", false);
    EXPECT_EQ(atrium.hiddenObjects, std::vector<std::string>{"Roof"});
    EXPECT_EQ(atrium.lightSampling, LightSampling::Split);
    EXPECT_EQ(atrium.bounces, 4);
    // The others trace two bounces, so that the arcades get the light bounced off the atrium.
    for (const char* name : {"sponza-static", "sponza-moving", "sponza-glossy", "sponza-light"})
        EXPECT_EQ(loadSceneDescription(name, "/s", false).bounces, 2) << name;
    EXPECT_EQ(loadSceneDescription("cornell-moving", "/s", false).bounces, 1);
    // Every Sponza preset aims its sky samples at the atrium's opening: one portal, 26.2 x 6.8.
    for (const char* name : {"sponza-atrium", "sponza-static", "sponza-light"}) {
        const Environment env = loadSceneDescription(name, "/s", false).environment;
        ASSERT_EQ(env.portals.size(), 1u) << name;
        EXPECT_NEAR(length(cross(env.portals[0].edgeU, env.portals[0].edgeV)), 26.2f * 6.8f, 1e-3f);
        EXPECT_NEAR(env.portals[0].corner.y, 22.3f, 1e-5f);
    }
    expectError(
        [] {
            parseSceneDescription(
                nlohmann::json::parse(R"({"mesh": "builtin:cornell", "sky": {"radiance": [1, 1, 1],
                    "portals": [{"centre": [0, 2, 0], "u": [1, 0, 0], "v": [2, 0, 0]}]}})"),
                ".");
        },
        "a sky portal has zero area");
    // The sunlit presets aim their bounces at the sunlit floor, on the atrium's floor (y 3.98);
    // the lamp-lit one has no sun and no guide.
    for (const char* name : {"sponza-atrium", "sponza-static", "sponza-moving", "sponza-glossy"}) {
        const Environment env = loadSceneDescription(name, "/s", false).environment;
        ASSERT_EQ(env.bounceGuides.size(), 1u) << name;
        EXPECT_NEAR(env.bounceGuides[0].corner.y, 3.99f, 1e-5f) << name;
        EXPECT_LT(env.sun.direction.x, 0.0f) << name; // from the far end, lighting the near floor
    }
    EXPECT_TRUE(loadSceneDescription("sponza-light", "/s", false).environment.bounceGuides.empty());
    const std::pair<const char*, const char*> badGuides[] = {
        {R"([{"centre": [0, 0, 0], "u": [1, 0, 0], "v": [0, 0, 0]}])",
         "a bounce guide has zero area"},
        {R"([{"centre": [0, 0, 0], "u": [1, 0, 0], "w": [0, 0, 1]}])", "bounce guide"},
    };
    for (const auto& [guides, message] : badGuides)
        expectError(
            [&] {
                parseSceneDescription(
                    nlohmann::json::parse(
                        std::string(R"({"mesh": "builtin:cornell", "bounce_guides": )") + guides +
                        "}"),
                    ".");
            },
            message);
    EXPECT_EQ(loadSceneDescription("cornell-objects", "/s", false).animations.size(), 3u);
    EXPECT_FLOAT_EQ(loadSceneDescription("sponza-glossy", "/s", false).roughnessOverride, 0.1f);
    EXPECT_EQ(loadSceneDescription("sponza-light", "/s", false).quadLights.size(), 1u);
    expectError([] { loadSceneDescription("no-such-preset", "."); },
                "presets: cornell-moving cornell-objects");
    // A Sponza preset whose mesh is not under --scenes says so, and names the flag.
    expectError([] { loadSceneDescription("sponza-moving", "no/such/dir"); },
                "with --scenes DIR (the relative 'no/such/dir' is read from");
}

TEST(RenderScene, HiddenObjectsLeaveTheSceneAndAnUnknownNameListsTheObjects) {
    Scene box = builtinCornellBox();
    const size_t all = box.triangleCount();
    size_t tall = 0;
    for (int o : box.triangleObject) tall += box.objectNames[size_t(o)] == "tall_block";
    ASSERT_GT(tall, 0u);
    box.removeObjects({"tall_block"});
    EXPECT_EQ(box.triangleCount(), all - tall);
    EXPECT_EQ(box.positions.size(), 3 * box.triangleCount());
    EXPECT_EQ(box.triangleObject.size(), box.triangleCount());
    for (int o : box.triangleObject) EXPECT_NE(box.objectNames[size_t(o)], "tall_block");
    expectError([&] { box.removeObjects({"roof"}); },
                "hide_objects names 'roof', but the scene has no such object (objects: room");
    auto parse = [](const std::string& text) {
        return parseSceneDescription(nlohmann::json::parse(text), ".");
    };
    const std::string base = R"({"mesh": "builtin:cornell", "camera": {"keyframes": [
        {"position": [0, 1, 3], "target": [0, 1, 0]}]})";
    EXPECT_EQ(parse(base + R"(, "hide_objects": ["tall_block"]})").hiddenObjects.size(), 1u);
    expectError([&] { parse(base + R"(, "hide_objects": "tall_block"})"); },
                "\"hide_objects\" must be a list of object names");
    expectError([&] { parse(base + R"(, "light_sampling": "all"})"); },
                "\"light_sampling\" is 'all', expected one or split");
    expectError([&] { parse(base + R"(, "light_sampling": "split", "paths": "mara"})"); },
                "\"light_sampling\": \"split\" is for the paper's paths");
}

TEST(RenderScene, SceneWithoutLightIsAnError) {
    fs::path d = testing::freshDir("render", "dark");
    std::ofstream(d / "m.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::ofstream(d / "dark.json") << R"({"mesh": "m.obj", "width": 8, "height": 8, "frames": 1,
        "camera": {"keyframes": [{"position": [0, 0, 3], "target": [0, 0, 0]}]}})";
    SceneDescription desc = loadSceneDescription((d / "dark.json").string(), ".");
    expectError(
        [&] {
            renderSequence(
                desc, {(d / "out").string()}, nullptr, [](int, int) {}, [](const std::string&) {});
        },
        "has no light");
    fs::remove_all(d);
}

TEST(RenderScene, ResumeSkipsFinishedFramesAndBothLayoutsAreReadable) {
    fs::path d = testing::freshDir("render", "resume");
    SceneDescription desc = loadSceneDescription("cornell-moving", ".");
    desc.width = 24, desc.height = 16, desc.frames = 3, desc.referenceSpp = 4;
    auto run = [&](const std::string& layout) {
        return renderSequence(
            desc, {(d / layout).string(), layout}, nullptr, [](int, int) {},
            [](const std::string&) {});
    };
    SequenceRenderReport first = run("manifest");
    EXPECT_EQ(first.rendered, 3);
    SequenceRenderReport again = run("manifest");
    EXPECT_EQ(again.rendered, 0);
    EXPECT_EQ(again.skipped, 3);
    fs::remove(d / "manifest" / "reference_0002.exr"); // an unfinished frame is rendered again
    EXPECT_EQ(run("manifest").rendered, 1);

    EXPECT_EQ(run("bmfr").rendered, 3);
    for (const char* layout : {"manifest", "bmfr"}) {
        auto reader = SequenceReader::open((d / layout).string());
        EXPECT_EQ(reader->info().frameCount, 3) << layout;
        EXPECT_TRUE(reader->info().hasReference) << layout;
        FrameData f;
        reader->load(2, f);
        EXPECT_EQ(f.color.width, 24);
    }
    // Both layouts carry the matrices the frames were rendered with.
    {
        FrameData a, b;
        SequenceReader::open((d / "manifest").string())->load(2, a);
        SequenceReader::open((d / "bmfr").string())->load(2, b);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                EXPECT_NEAR(a.viewProjection.m[r][c], b.viewProjection.m[r][c],
                            1e-6f * (1 + std::fabs(a.viewProjection.m[r][c])));
    }
    // The AOVs come back from our own layout on request.
    auto reader = SequenceReader::open((d / "manifest").string());
    reader->setLoadAovs(true);
    FrameData f;
    reader->load(1, f);
    ASSERT_EQ(f.aovs.size(), 5u);
    EXPECT_EQ(f.aovs[0].first, "depth");
    EXPECT_EQ(f.aovs[0].second.channels, 1);
    // Motion vectors are an input of their own; a static scene has no previous positions.
    EXPECT_EQ(f.motion.channels, 3); // with the depth offset
    EXPECT_EQ(f.diffuseIndirect.channels, 3);
    EXPECT_EQ(f.previousPosition.width, 0);
    fs::remove_all(d);
}

TEST(RenderScene, CancelStopsWithoutWritingAFrame) {
    fs::path d = testing::freshDir("render", "cancel");
    SceneDescription desc = loadSceneDescription("cornell-moving", ".");
    desc.width = 16, desc.height = 16, desc.frames = 2, desc.referenceSpp = 2;
    std::atomic<bool> cancel{true};
    SequenceRenderReport r = renderSequence(
        desc, {d.string()}, &cancel, [](int, int) {}, [](const std::string&) {});
    EXPECT_TRUE(r.interrupted);
    EXPECT_EQ(r.rendered, 0);
    EXPECT_FALSE(fs::exists(d / "color_0000.exr"));
    for (const auto& e : fs::directory_iterator(d))
        EXPECT_EQ(e.path().extension(), ".json") << e.path();
    fs::remove_all(d);
}

} // namespace
} // namespace bmfr::render
