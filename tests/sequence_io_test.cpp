// Reading the original BMFR dataset layout and this project's layout; bad files get clear errors.
#include "core/mat4.h"
#include "io/exr.h"
#include "io/sequence.h"
#include "synth/procedural_scene.h"
#include "test_support.h"
#include <bmfr/error.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;

ImageF filled(int w, int h, float base) {
    ImageF img(w, h, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = base + 0.001f * float(i);
    return img;
}

/// A 2-frame, 5x3 sequence in the original layout, with camera_matrices.h written by hand.
fs::path writeOriginalLayout() {
    fs::path d = testing::freshDir("test", "original");
    for (int n = 0; n < 2; ++n) {
        writeExr((d / ("color" + std::to_string(n) + ".exr")).string(), filled(5, 3, 1.0f + n));
        writeExr((d / ("albedo" + std::to_string(n) + ".exr")).string(), filled(5, 3, 0.5f));
        writeExr((d / ("shading_normal" + std::to_string(n) + ".exr")).string(),
                 filled(5, 3, 0.1f));
        writeExr((d / ("world_position" + std::to_string(n) + ".exr")).string(),
                 filled(5, 3, 7.0f));
        writeExr((d / ("reference" + std::to_string(n) + ".exr")).string(), filled(5, 3, 2.0f));
    }
    std::ofstream(d / "camera_matrices.h") << R"(// camera data
#pragma once
const float position_limit_squared = 0.002500f;
const float normal_limit_squared = 0.25;  /* about 29 degrees */
const float camera_matrices[2][4][4] = {
 { {1.5f, 0.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f, 0.0f},
   {0.0f, 0.0f, -1.0f, -1.0f}, {0.25f, 0.5f, -0.2f, 3.0f} },
 { {1.5f, 0.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f, 0.0f},
   {0.0f, 0.0f, -1.0f, -1.0f}, {-1e-1f, 0.5f, -0.2f, 3.0f} },
};
const float pixel_offsets[2][2] = { {0.5f, 0.5f}, {0.25f, 0.75f} };
)";
    return d;
}

TEST(SequenceIO, ReadsTheOriginalBmfrLayout) {
    fs::path d = writeOriginalLayout();
    auto reader = SequenceReader::open(d.string());
    const SequenceInfo& info = reader->info();
    EXPECT_EQ(info.layout, "bmfr");
    EXPECT_EQ(info.frameCount, 2);
    EXPECT_EQ(info.width, 5);
    EXPECT_EQ(info.height, 3);
    EXPECT_TRUE(info.colorIsDemodulated);
    EXPECT_TRUE(info.hasReference);
    EXPECT_FLOAT_EQ(*info.positionLimitSquared, 0.0025f);
    EXPECT_FLOAT_EQ(*info.normalLimitSquared, 0.25f);

    FrameData f;
    reader->load(1, f);
    EXPECT_FLOAT_EQ(f.color.at(4, 2, 1), 2.0f + 0.001f * float((2 * 5 + 4) * 3 + 1));
    EXPECT_FLOAT_EQ(f.position.at(0, 0, 0), 7.0f);
    EXPECT_FLOAT_EQ(f.reference.at(1, 0, 2), 2.0f + 0.001f * 5);
    // Row vectors in the file: our matrix is the transpose (x' = 1.5x - 0.1 w).
    EXPECT_FLOAT_EQ(f.viewProjection.m[0][0], 1.5f);
    EXPECT_FLOAT_EQ(f.viewProjection.m[0][3], -0.1f);
    EXPECT_FLOAT_EQ(f.viewProjection.m[3][2], -1.0f);
    EXPECT_FLOAT_EQ(f.viewProjection.m[2][3], -0.2f);
    // Frame 0 carries offset 1 (the authors' code reprojects frame 1 with it): (x-0.5, 0.5-y).
    reader->load(0, f);
    EXPECT_FLOAT_EQ(f.jitter[0], -0.25f);
    EXPECT_FLOAT_EQ(f.jitter[1], -0.25f);
    fs::remove_all(d);
}

TEST(SequenceIO, CameraFileErrorsAreSpecific) {
    EXPECT_THROW(parseBmfrCameraFile("const float x = 1;", "a.h"), Error);
    try {
        parseBmfrCameraFile("float camera_matrices[2][4][4] = {{1,2,3,4, 5,6,7,8, 9,10,11,12, "
                            "13,14,15,16}};",
                            "b.h");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("declared [2][4][4] but holds 1"), std::string::npos)
            << e.what();
    }
    EXPECT_THROW(parseBmfrCameraFile("float camera_matrices[1][4][4] = {{1,2,3}};", "c.h"), Error);
}

TEST(SequenceIO, BadFilesNameTheFileAndFrame) {
    fs::path d = writeOriginalLayout();
    auto reader = SequenceReader::open(d.string());
    FrameData f;
    auto expectError = [&](int frame, const std::string& needle) {
        try {
            reader->load(frame, f);
            ADD_FAILURE() << "no error, expected " << needle;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    fs::remove(d / "albedo1.exr");
    expectError(1, "missing file: " + (d / "albedo1.exr").string());
    std::ofstream(d / "albedo1.exr") << "not an exr";
    expectError(1, "unreadable EXR " + (d / "albedo1.exr").string());
    writeExr((d / "albedo1.exr").string(), filled(4, 3, 0.5f));
    expectError(1, "frame 1 albedo is 4x3, the sequence is 5x3");
    ImageF single(5, 3, 2); // R,G only: no B channel
    writeExr((d / "albedo1.exr").string(), single);
    expectError(1, "expected R,G,B");
    fs::remove_all(d);

    EXPECT_THROW(SequenceReader::open("/nonexistent/bmfr"), Error);
    fs::path empty = testing::freshDir("test", "empty");
    EXPECT_THROW(SequenceReader::open(empty.string()), Error);
    fs::remove_all(empty);
}

TEST(SequenceIO, ManifestAndOriginalLayoutRoundTrip) {
    ProceduralSceneOptions o;
    o.width = 24, o.height = 16, o.frames = 3;
    ProceduralScene scene(o);
    std::vector<FrameData> frames(3);
    fs::path dm = testing::freshDir("test", "manifest"),
             db = testing::freshDir("test", "bmfrlayout");
    {
        ManifestWriter w(dm.string(), scene.info());
        for (int i = 0; i < 3; ++i) scene.render(i, frames[i]), w.addFrame(i, frames[i]);
    }
    writeBmfrLayout(db.string(), frames, 0.01f, 1.0f);
    auto rm = SequenceReader::open(dm.string()), rb = SequenceReader::open(db.string());
    EXPECT_EQ(rm->info().layout, "manifest");
    EXPECT_EQ(rm->info().extraNames, std::vector<std::string>{"material_id"});
    EXPECT_EQ(rb->info().frameCount, 3);
    for (int i = 0; i < 3; ++i) {
        FrameData a, b;
        rm->load(i, a);
        rb->load(i, b);
        EXPECT_EQ(a.color.pixels, frames[i].color.pixels);
        EXPECT_EQ(a.extras.at(0).pixels, frames[i].extras[0].pixels);
        EXPECT_EQ(b.position.pixels, frames[i].position.pixels);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) {
                EXPECT_EQ(a.viewProjection.m[r][c], frames[i].viewProjection.m[r][c]);
                EXPECT_NEAR(b.viewProjection.m[r][c], frames[i].viewProjection.m[r][c],
                            1e-6 * (1 + std::fabs(frames[i].viewProjection.m[r][c])));
            }
        // The original layout stores demodulated colour.
        EXPECT_NEAR(b.color.at(3, 4, 0) * std::max(b.albedo.at(3, 4, 0), 0.001f),
                    frames[i].color.at(3, 4, 0), 1e-5);
        if (i < 2) { // the jitter of the last frame is never used, nor stored
            EXPECT_NEAR(b.jitter[0], frames[i].jitter[0], 1e-6);
            EXPECT_NEAR(b.jitter[1], frames[i].jitter[1], 1e-6);
        }
    }
    fs::remove_all(dm);
    fs::remove_all(db);
}

TEST(SequenceIO, ZeroSizeManifestIsRejected) {
    fs::path d = testing::freshDir("test", "zero");
    std::ofstream(d / "sequence.json")
        << R"({"format": "bmfr-sequence", "version": 1, "width": 0, "height": 10, "frames": []})";
    try {
        SequenceReader::open(d.string());
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("zero-size"), std::string::npos) << e.what();
    }
    fs::remove_all(d);
}

} // namespace
} // namespace bmfr
