// Multilayer and multi-part EXR input, as Blender's Cycles writes it: layer and channel names,
// the default pass mapping, --channel overrides and the errors that name what is missing.
#include "cli_runner.h"
#include "io/exr.h"
#include "io/sequence.h"
#include "test_support.h"
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <bmfr/error.h>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <unistd.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;
constexpr int kLayerW = 6, kLayerH = 4;

/// The value a test file holds at pixel i of channel `name`: distinct per channel.
float valueOf(const std::string& name, int i) {
    return float(std::hash<std::string>{}(name) % 1000) * 0.001f + float(i);
}

/// One part holding `channels` (full names), each filled with valueOf(name, i).
void writeLayered(const fs::path& path, const std::vector<std::string>& channels) {
    Imf::Header header(kLayerW, kLayerH);
    for (const std::string& c : channels) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    std::vector<std::vector<float>> data;
    Imf::FrameBuffer fb;
    for (const std::string& c : channels) {
        data.emplace_back(kLayerW * kLayerH);
        for (int i = 0; i < kLayerW * kLayerH; ++i) data.back()[size_t(i)] = valueOf(c, i);
        fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.back().data()),
                                sizeof(float), sizeof(float) * kLayerW));
    }
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(kLayerH);
}

/// Parts named after layers, each with plain R,G,B (or X,Y,Z) channels.
void writeMultiPart(const fs::path& path, const std::map<std::string, std::string>& parts) {
    std::vector<Imf::Header> headers;
    for (const auto& [name, xyz] : parts) {
        Imf::Header h(kLayerW, kLayerH);
        h.setName(name);
        h.setType(Imf::SCANLINEIMAGE);
        for (char c : xyz) h.channels().insert(std::string(1, c), Imf::Channel(Imf::FLOAT));
        headers.push_back(h);
    }
    Imf::MultiPartOutputFile file(path.c_str(), headers.data(), int(headers.size()));
    int p = 0;
    for (const auto& [name, xyz] : parts) {
        std::vector<std::vector<float>> data;
        data.reserve(xyz.size());
        Imf::FrameBuffer fb;
        for (char c : xyz) {
            const std::string full = name + "." + std::string(1, c);
            data.emplace_back(kLayerW * kLayerH);
            for (int i = 0; i < kLayerW * kLayerH; ++i) data.back()[size_t(i)] = valueOf(full, i);
            fb.insert(std::string(1, c),
                      Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data.back().data()),
                                 sizeof(float), sizeof(float) * kLayerW));
        }
        Imf::OutputPart part(file, p++);
        part.setFrameBuffer(fb);
        part.writePixels(kLayerH);
    }
}

void expectChannels(const ImageF& img, const std::vector<std::string>& names) {
    ASSERT_EQ(img.width, kLayerW);
    ASSERT_EQ(img.channels, int(names.size()));
    for (int i = 0; i < kLayerW * kLayerH; ++i)
        for (size_t c = 0; c < names.size(); ++c)
            ASSERT_EQ(img.data()[i * img.channels + int(c)], valueOf(names[c], i)) << names[c];
}

using testing::errorOf;

const std::vector<std::string> kCyclesChannels = {"ViewLayer.Combined.R",
                                                  "ViewLayer.Combined.G",
                                                  "ViewLayer.Combined.B",
                                                  "ViewLayer.Combined.A",
                                                  "ViewLayer.Denoising Albedo.R",
                                                  "ViewLayer.Denoising Albedo.G",
                                                  "ViewLayer.Denoising Albedo.B",
                                                  "ViewLayer.DiffCol.R",
                                                  "ViewLayer.DiffCol.G",
                                                  "ViewLayer.DiffCol.B",
                                                  "ViewLayer.Normal.X",
                                                  "ViewLayer.Normal.Y",
                                                  "ViewLayer.Normal.Z",
                                                  "ViewLayer.Position.X",
                                                  "ViewLayer.Position.Y",
                                                  "ViewLayer.Position.Z",
                                                  "ViewLayer.Emit.R",
                                                  "ViewLayer.Emit.G",
                                                  "ViewLayer.Emit.B",
                                                  "ViewLayer.Depth.Z"};

TEST(MultilayerExr, LayersAndChannelNamesAsCyclesWritesThem) {
    const fs::path dir = testing::freshDir("ml", "layers");
    const fs::path f = dir / "frame.exr";
    writeLayered(f, kCyclesChannels);
    expectChannels(readExr(f.string(), 3, "ViewLayer.Combined"),
                   {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"});
    expectChannels(readExr(f.string(), 3, "ViewLayer.Normal"),
                   {"ViewLayer.Normal.X", "ViewLayer.Normal.Y", "ViewLayer.Normal.Z"});
    expectChannels(readExr(f.string(), 1, "ViewLayer.Depth"), {"ViewLayer.Depth.Z"});
    EXPECT_EQ(findExrLayer(f.string(), "Denoising Albedo"), "ViewLayer.Denoising Albedo");
    EXPECT_EQ(findExrLayer(f.string(), "Albedo"), ""); // whole pass names only
    EXPECT_EQ(findExrLayer(f.string(), "Glossy"), "");
    // No plain channels: reading without a layer names what the file has.
    const std::string e = errorOf([&] { readExr(f.string(), 3); });
    EXPECT_NE(e.find("ViewLayer.Normal.X"), std::string::npos) << e;
    EXPECT_NE(errorOf([&] { readExr(f.string(), 3, "ViewLayer.Nope"); }).find("in layer"),
              std::string::npos);
    fs::remove_all(dir);
}

TEST(MultilayerExr, MultiPartFilesNameLayersByPart) {
    const fs::path dir = testing::freshDir("ml", "parts");
    const fs::path f = dir / "parts.exr";
    writeMultiPart(f, {{"ViewLayer.Combined", "RGB"}, {"ViewLayer.Normal", "XYZ"}});
    EXPECT_EQ(exrChannelNames(f.string()).size(), 6u);
    expectChannels(readExr(f.string(), 3, "ViewLayer.Normal"),
                   {"ViewLayer.Normal.X", "ViewLayer.Normal.Y", "ViewLayer.Normal.Z"});
    expectChannels(readExr(f.string(), 3, "ViewLayer.Combined"),
                   {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"});
    fs::remove_all(dir);
}

TEST(MultilayerExr, SequencesUseTheDefaultPassesAndChannelOverrides) {
    const fs::path dir = testing::freshDir("ml", "sequence");
    writeLayered(dir / "frame_0000.exr", kCyclesChannels);
    std::ofstream(dir / "sequence.json") << R"({"format": "bmfr-sequence", "version": 1,
        "width": 6, "height": 4, "frames": [{"color": "frame_0000.exr",
        "albedo": "frame_0000.exr", "normal": "frame_0000.exr", "position": "frame_0000.exr",
        "emission": {"file": "frame_0000.exr", "layer": "ViewLayer.Emit"},
        "view_projection": [[1,0,0,0],[0,1,0,0],[0,0,-1,-0.2],[0,0,-1,0]]}]})";
    auto reader = SequenceReader::open(dir.string());
    FrameData f;
    reader->load(0, f);
    expectChannels(f.color,
                   {"ViewLayer.Combined.R", "ViewLayer.Combined.G", "ViewLayer.Combined.B"});
    expectChannels(f.albedo, {"ViewLayer.Denoising Albedo.R", "ViewLayer.Denoising Albedo.G",
                              "ViewLayer.Denoising Albedo.B"});
    expectChannels(f.position,
                   {"ViewLayer.Position.X", "ViewLayer.Position.Y", "ViewLayer.Position.Z"});
    expectChannels(f.emission, {"ViewLayer.Emit.R", "ViewLayer.Emit.G", "ViewLayer.Emit.B"});
    reader->setLayerOverrides({{"albedo", "ViewLayer.DiffCol"}});
    reader->load(0, f);
    expectChannels(f.albedo, {"ViewLayer.DiffCol.R", "ViewLayer.DiffCol.G", "ViewLayer.DiffCol.B"});
    EXPECT_NE(errorOf([&] {
                  reader->setLayerOverrides({{"colour", "X"}});
              }).find("unknown buffer"),
              std::string::npos);
    reader->setLayerOverrides({{"normal", "ViewLayer.Nope"}});
    EXPECT_NE(errorOf([&] { reader->load(0, f); }).find("in layer 'ViewLayer.Nope'"),
              std::string::npos);
    // The same through the CLI: --channel, and a bad one is a clear error.
    const fs::path out = dir / "out";
    auto ok = testing::runCli("denoise " + dir.string() + " -o " + out.string() +
                              " -q --channel albedo=ViewLayer.DiffCol");
    EXPECT_EQ(ok.code, 0) << ok.output;
    auto bad = testing::runCli("denoise " + dir.string() + " -o " + out.string() +
                               " -q --channel position=ViewLayer.Normalz");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("in layer 'ViewLayer.Normalz'"), std::string::npos) << bad.output;
    fs::remove_all(dir);
}

// Cycles' Vector pass (X, Y: the previous frame's screen position minus this one's, pixels, y
// up, through this frame's projection, so without the lens-shift jitter) read under
// "motion_convention": "cycles" becomes bmfr's motion, (X, -Y) + jitter - previous jitter, and
// the previous position is an offset from the position, by hand here; without the convention it is
// an error, as is a --channel for a buffer the frames do not name (it used to be ignored).
TEST(MultilayerExr, CyclesVectorPassBecomesMotionWithTheJitter) {
    const fs::path dir = testing::freshDir("ml", "cycles_vector");
    std::vector<std::string> channels = kCyclesChannels;
    for (const char* c : {"X", "Y", "Z", "W"})
        channels.push_back(std::string("ViewLayer.Vector.") + c);
    writeLayered(dir / "frame_0000.exr", channels);
    writeLayered(dir / "frame_0001.exr", channels);
    const std::string frame = R"("color": "F", "albedo": "F", "normal": "F", "position": "F",
        "motion": "F", "previous_position": {"file": "F", "layer": "ViewLayer.Emit"},
        "view_projection": [[1,0,0,0],[0,1,0,0],[0,0,-1,-0.2],[0,0,-1,0]])";
    auto entry = [&](const char* file, const char* jitter) {
        std::string e = frame;
        for (size_t p; (p = e.find("\"F\"")) != std::string::npos;)
            e.replace(p, 3, std::string("\"") + file + "\"");
        return "{" + e + ", \"jitter\": " + jitter + "}";
    };
    auto write = [&](const std::string& convention) {
        std::ofstream(dir / "sequence.json")
            << R"({"format": "bmfr-sequence", "version": 1, "width": 6, "height": 4, )" +
                   convention + R"("frames": [)" + entry("frame_0000.exr", "[0.25, -0.125]") +
                   ", " + entry("frame_0001.exr", "[-0.375, 0.0625]") + "]}";
    };
    write(R"("motion_convention": "cycles", )");
    auto reader = SequenceReader::open(dir.string());
    FrameData f;
    reader->load(1, f);
    ASSERT_EQ(f.motion.channels, 2);
    const float dx = -0.375f - 0.25f, dy = 0.0625f - -0.125f;
    for (int i = 0; i < kLayerW * kLayerH; ++i) {
        EXPECT_EQ(f.motion.data()[2 * i], valueOf("ViewLayer.Vector.X", i) + dx);
        EXPECT_EQ(f.motion.data()[2 * i + 1], -valueOf("ViewLayer.Vector.Y", i) + dy);
        // The previous position is an offset from the position under this convention.
        const char *rgb[] = {"R", "G", "B"}, *xyz[] = {"X", "Y", "Z"};
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(f.previousPosition.data()[3 * i + c],
                      valueOf(std::string("ViewLayer.Emit.") + rgb[c], i) +
                          valueOf(std::string("ViewLayer.Position.") + xyz[c], i));
    }
    write("");
    const std::string e = errorOf([&] { SequenceReader::open(dir.string())->load(1, f); });
    EXPECT_NE(e.find("motion_convention"), std::string::npos) << e;
    write(R"("motion_convention": "blender", )");
    EXPECT_NE(errorOf([&] { SequenceReader::open(dir.string()); }).find("\"blender\""),
              std::string::npos);
    // A layer for a buffer the frames do not name is an error, not ignored.
    std::ofstream(dir / "sequence.json")
        << R"({"format": "bmfr-sequence", "version": 1, "width": 6, "height": 4, "frames": [{)"
        << R"("color": "frame_0000.exr", "albedo": "frame_0000.exr", "normal": "frame_0000.exr",
        "position": "frame_0000.exr",
        "view_projection": [[1,0,0,0],[0,1,0,0],[0,0,-1,-0.2],[0,0,-1,0]]}]})";
    const auto r = testing::runCli("denoise " + dir.string() + " -o " + (dir / "out").string() +
                                   " -q --no-png --channel motion=ViewLayer.Vector");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("names no motion file"), std::string::npos) << r.output;
    fs::remove_all(dir);
}

// `bmfr tonemap` and imageLayer (bmfr.read_exr's default): a multilayer render gives its
// Combined pass, --layer another; a file with neither plain channels nor Combined names its
// layers.
TEST(MultilayerExr, TonemapReadsTheCombinedPassOrTheLayerNamed) {
    const fs::path dir = testing::freshDir("ml", "tonemap");
    writeLayered(dir / "render.exr", kCyclesChannels);
    EXPECT_EQ(imageLayer((dir / "render.exr").string()), "ViewLayer.Combined");
    auto run = [&](const std::string& args) {
        return testing::runCli("tonemap " + (dir / "render.exr").string() + " -o " +
                               (dir / "out.png").string() + args);
    };
    EXPECT_EQ(run("").code, 0);
    EXPECT_EQ(run(" --layer ViewLayer.Emit").code, 0);
    const auto bad = run(" --layer ViewLayer.Nope");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("in layer 'ViewLayer.Nope'"), std::string::npos) << bad.output;
    writeLayered(dir / "passes.exr", {"ViewLayer.Emit.R", "ViewLayer.Emit.G", "ViewLayer.Emit.B"});
    const std::string e = errorOf([&] { imageLayer((dir / "passes.exr").string()); });
    EXPECT_NE(e.find("no Combined pass; name a layer (ViewLayer.Emit)"), std::string::npos) << e;
    fs::remove_all(dir);
}

// A Cycles render with its own denoiser on (tests/data/make_cycles_denoiser_on.py) holds both
// Combined, the denoised result, and Noisy Image: the noisy one is read, and the run says so.
TEST(MultilayerExr, CyclesOwnDenoiserIsNoticedAndItsNoisyImageRead) {
    const fs::path file = fs::path(BMFR_SOURCE_DIR) / "tests" / "data" / "cycles_denoiser_on.exr";
    const fs::path dir = testing::freshDir("ml", "cycles_denoiser");
    fs::copy_file(file, dir / "frame_0000.exr");
    fs::copy_file(file, dir / "frame_0001.exr");
    std::ofstream(dir / "sequence.json") << R"({"format": "bmfr-sequence", "version": 1,
        "width": 24, "height": 16, "frames": [{"color": "frame_0000.exr",
        "albedo": "frame_0000.exr", "normal": "frame_0000.exr", "position": "frame_0000.exr",
        "view_projection": [[1,0,0,0],[0,1,0,0],[0,0,-1,-0.2],[0,0,-1,0]]},
        {"color": "frame_0001.exr", "albedo": "frame_0001.exr", "normal": "frame_0001.exr",
        "position": "frame_0001.exr",
        "view_projection": [[1,0,0,0],[0,1,0,0],[0,0,-1,-0.2],[0,0,-1,0]]}]})";
    const ImageF noisy = readExr(file.string(), 3, "ViewLayer.Noisy Image");
    const ImageF denoised = readExr(file.string(), 3, "ViewLayer.Combined");
    ASSERT_NE(noisy.pixels, denoised.pixels);
    auto reader = SequenceReader::open(dir.string());
    FrameData f;
    reader->load(0, f);
    EXPECT_EQ(f.color.pixels, noisy.pixels);
    reader->load(1, f);
    ASSERT_EQ(reader->notes().size(), 1u) << "one note for the sequence, not one per frame";
    EXPECT_NE(reader->notes()[0].find("Cycles' own denoiser was on"), std::string::npos)
        << reader->notes()[0];
    // A layer the user names is taken as it is, without a note.
    auto chosen = SequenceReader::open(dir.string());
    chosen->setLayerOverrides({{"color", "ViewLayer.Combined"}});
    chosen->load(0, f);
    EXPECT_EQ(f.color.pixels, denoised.pixels);
    EXPECT_TRUE(chosen->notes().empty());
    const auto r = testing::runCli("denoise " + dir.string() + " -o " + (dir / "out").string() +
                                   " -q --no-png");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("bmfr: note: Cycles' own denoiser was on"), std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("bmfr: note:"), r.output.rfind("bmfr: note:")) << r.output;
}

} // namespace
} // namespace bmfr
