// Regression tests of the hardening findings (../shared/repro and the issue's list): each bad
// input is a clear error, never a crash, a hang, a huge allocation or silent garbage, and no
// write loses a user's data.
#include "cli_runner.h"
#include "eval/comparison.h"
#include "io/atomic_file.h"
#include "io/exr.h"
#include "io/sequence.h"
#include "render/scene_description.h"
#include "render/sequence_renderer.h"
#include "synth/procedural_scene.h"
#include "test_support.h"
#include <array>
#include <bmfr/bmfr.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <sys/wait.h>

namespace bmfr {
namespace {

namespace fs = std::filesystem;

fs::path repro(const char* name) {
    return fs::path(BMFR_SOURCE_DIR) / ".." / "shared" / "repro" / name;
}
#define REQUIRE_REPRO(name)                                                                        \
    if (!fs::exists(repro(name))) GTEST_SKIP() << "no ../shared/repro/" << name

using testing::errorOf;
#define EXPECT_ERROR(call, needle)                                                                 \
    do {                                                                                           \
        const std::string what_ = errorOf([&] { call; });                                          \
        EXPECT_NE(what_.find(needle), std::string::npos) << what_;                                 \
    } while (0)

using Result = bmfr::testing::CliResult;
Result run(const std::string& args) {
    return bmfr::testing::runCli(args);
}

using testing::slurp;

using testing::proceduralFrames;

render::SceneDescription tinyScene() {
    render::SceneDescription d = render::loadSceneDescription("cornell-moving", ".");
    d.width = 12, d.height = 8, d.frames = 2, d.referenceSpp = 2;
    return d;
}
render::SequenceRenderReport renderInto(const render::SceneDescription& d, const fs::path& dir,
                                        const std::string& layout, bool overwrite = false) {
    return render::renderSequence(
        d, {dir.string(), layout, true, overwrite}, nullptr, [](int, int) {},
        [](const std::string&) {});
}

// 1. Data loss: a folder holding another dataset is refused, and nothing in it is touched.
TEST(Hardening, RenderRefusesAFolderHoldingAnotherDataset) {
    const fs::path dir = testing::freshDir("hard", "dataset");
    writeBmfrLayout(dir.string(), proceduralFrames(12, 8, 2), 0.01f, 1.0f);
    const std::string before = slurp(dir / "camera_matrices.h");
    EXPECT_ERROR(renderInto(tinyScene(), dir, "bmfr"), "refusing to write into it");
    EXPECT_EQ(slurp(dir / "camera_matrices.h"), before);
    // With --overwrite the render replaces it, frames and matrices together.
    EXPECT_EQ(renderInto(tinyScene(), dir, "bmfr", true).rendered, 2);
    EXPECT_NE(slurp(dir / "camera_matrices.h"), before);
    fs::remove_all(dir);
}

TEST(Hardening, RenderResumesOnlyTheSameSceneAndSettings) {
    const fs::path dir = testing::freshDir("hard", "fingerprint");
    render::SceneDescription d = tinyScene();
    EXPECT_EQ(renderInto(d, dir, "manifest").rendered, 2);
    EXPECT_EQ(renderInto(d, dir, "manifest").skipped, 2);
    d.frames = 3; // a longer run of the same scene resumes
    EXPECT_EQ(renderInto(d, dir, "manifest").rendered, 1);
    render::SceneDescription other = d;
    other.seed = 99;
    EXPECT_ERROR(renderInto(other, dir, "manifest"), "another scene, settings or layout");
    EXPECT_ERROR(renderInto(d, dir, "bmfr"), "another scene, settings or layout");
    fs::remove_all(dir);
}

TEST(Hardening, BmfrLayoutHeaderIsWrittenAfterItsFrames) {
    const fs::path dir = testing::freshDir("hard", "header_last");
    std::atomic<bool> cancel{true}; // stopped before the first frame
    render::renderSequence(
        tinyScene(), {dir.string(), "bmfr", true}, &cancel, [](int, int) {},
        [](const std::string&) {});
    EXPECT_FALSE(fs::exists(dir / "camera_matrices.h"));
    EXPECT_FALSE(fs::exists(dir / "color0.exr"));
    fs::remove_all(dir);
}

// 2, 5. Scene descriptions: a zero sun, degenerate cameras, unknown keys, wrapped integers.
TEST(Hardening, DegenerateScenesAreErrors) {
    REQUIRE_REPRO("render-sun-zero-direction.json");
    EXPECT_ERROR(render::loadSceneDescription(repro("render-sun-zero-direction.json"), "."),
                 "sun.direction must not be zero");
    EXPECT_ERROR(render::loadSceneDescription(repro("render-camera-look-down.json"), "."),
                 "looks along its up vector");
    EXPECT_ERROR(render::loadSceneDescription(repro("render-camera-pos-eq-target.json"), "."),
                 "position equal to its target");
    auto parse = [](const std::string& extra) {
        return render::parseSceneDescription(
            nlohmann::json::parse(R"({"mesh": "builtin:cornell", )" + extra +
                                  R"("camera": {"keyframes": [{"position": [0, 1, 3],
                                     "target": [0, 1, 0]}]}})"),
            ".");
    };
    EXPECT_ERROR(parse(R"("widht": 64, )"), "unknown key 'widht' in scene description (did you "
                                            "mean 'width'?)");
    EXPECT_ERROR(parse(R"("width": 4294967312, )"), "width = 4294967312 is outside [1, 16384]");
    EXPECT_ERROR(parse(R"("width": 12.5, )"), "width must be a whole number");
    EXPECT_ERROR(parse(R"("frames": 2000000000, )"), "frames = 2000000000 is outside");
    EXPECT_ERROR(parse(R"("lights": [{"type": "quad", "centre": [0, 1, 0], "u": [0, 0, 0],
                          "v": [0, 0, 1], "radiance": [1, 1, 1]}], )"),
                 "zero area");
    EXPECT_ERROR(parse(R"("camera_typo": 1, )"), "unknown key 'camera_typo'");
    render::SceneDescription d = tinyScene();
    d.width = 20000; // as --width would set it
    EXPECT_ERROR(render::validate(d), "outside [1, 16384]");
}

// 3. The camera header parser stops on text that opens '[' and never closes it.
TEST(Hardening, CameraHeaderParserCannotHang) {
    REQUIRE_REPRO("camera-hang-min.h");
    const auto start = std::chrono::steady_clock::now();
    EXPECT_ERROR(parseBmfrCameraFile(slurp(repro("camera-hang-min.h")), "camera_matrices.h"),
                 "never closes it");
    EXPECT_ERROR(parseBmfrCameraFile("float camera_matrices[-3][4][4] = {1};", "x"),
                 "is not a count");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

// 4. An EXR that claims far more pixels than it holds fails before allocating them.
TEST(Hardening, ExrClaimingAHugeImageFailsFast) {
    REQUIRE_REPRO("exr-claims-16384x16384-8KB.exr");
    const auto start = std::chrono::steady_clock::now();
    EXPECT_ERROR(readExr(repro("exr-claims-16384x16384-8KB.exr").string(), 3),
                 "truncated or corrupt");
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

// 5. Manifests whose sizes overflow or wrap through int.
TEST(Hardening, ManifestSizesAreCheckedIntegers) {
    REQUIRE_REPRO("manifest-width-1e20.json");
    for (const char* name : {"manifest-width-1e20.json", "manifest-width-wrap.json"}) {
        const fs::path dir = testing::freshDir("hard", "manifest");
        fs::copy_file(repro(name), dir / "sequence.json");
        EXPECT_ERROR(SequenceReader::open(dir.string()), "width");
        fs::remove_all(dir);
    }
}

TEST(Hardening, ManifestKeysAreChecked) {
    const fs::path dir = testing::freshDir("hard", "manifest_keys");
    ProceduralSceneOptions o;
    o.width = 8, o.height = 4, o.frames = 1;
    ManifestWriter(dir.string(), ProceduralScene(o).info())
        .addFrame(0, proceduralFrames(8, 4, 1)[0]);
    std::string text = slurp(dir / "sequence.json");
    text.replace(text.find("\"albedo\""), 8, "\"albedoo\"");
    std::ofstream(dir / "sequence.json") << text;
    EXPECT_ERROR(SequenceReader::open(dir.string()), "unknown key 'albedoo' in " +
                                                         (dir / "sequence.json").string() +
                                                         " frame 0 (did you mean 'albedo'?)");
    fs::remove_all(dir);
}

TEST(Hardening, SynthRejectsANonFiniteCameraSpeed) {
    ProceduralSceneOptions o;
    o.cameraSpeed = NAN;
    EXPECT_ERROR(ProceduralScene{o}, "camera speed");
    Result r = run("synth -o /tmp/bmfr_never_written --camera-speed nan -q");
    EXPECT_EQ(r.code, 1) << r.output;
}

// 6. Writes are checked: a failure names the path and the reason and leaves no partial file.
TEST(Hardening, FailedWritesAreErrorsWithThePath) {
    const fs::path dir = testing::freshDir("hard", "writes");
    std::ofstream(dir / "file") << "x";
    const std::string bad = (dir / "file" / "report.json").string(); // a file as a folder
    EXPECT_ERROR(writeFileAtomically(bad, std::string("{}")), "cannot write " + bad);
    writeFileAtomically((dir / "ok.json").string(), std::string("{}"));
    EXPECT_EQ(slurp(dir / "ok.json"), "{}");
    EXPECT_FALSE(fs::exists(dir / "ok.json.part"));
    ASSERT_EQ(
        run("synth -o " + (dir / "in").string() + " --width 16 --height 8 --frames 2 -q").code, 0);
    Result r = run("denoise " + (dir / "in").string() + " -o " + (dir / "file").string() + " -q");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("bmfr: error"), std::string::npos) << r.output;
    fs::remove_all(dir);
}

// 7. The smaller ones.
TEST(Hardening, TonemapNeverOverwritesItsInput) {
    const fs::path dir = testing::freshDir("hard", "tonemap");
    ImageF img(4, 3, 3);
    writeExr((dir / "x.exr").string(), img);
    const std::string before = slurp(dir / "x.exr");
    Result r = run("tonemap " + (dir / "x.exr").string() + " -o " + (dir / "x.exr").string());
    EXPECT_EQ(r.code, 2); // the command line names one file twice
    EXPECT_NE(r.output.find("refusing to overwrite"), std::string::npos) << r.output;
    EXPECT_EQ(slurp(dir / "x.exr"), before);
    fs::remove_all(dir);
}

TEST(Hardening, IncompleteSequencesAreErrors) {
    const fs::path dir = testing::freshDir("hard", "gaps");
    ProceduralSceneOptions o;
    o.width = 12, o.height = 8, o.frames = 4;
    const ProceduralScene scene(o);
    const std::vector<FrameData> frames = proceduralFrames(12, 8, 4);
    writeBmfrLayout((dir / "bmfr").string(), frames, 0.01f, 1.0f);
    fs::remove(dir / "bmfr" / "color2.exr");
    EXPECT_ERROR(SequenceReader::open((dir / "bmfr").string()),
                 "color2.exr is missing, yet color3.exr exists");
    // A manifest whose first frame lacks the reference the others have.
    ManifestWriter w((dir / "manifest").string(), scene.info());
    for (int i = 0; i < 2; ++i) {
        FrameData f = frames[size_t(i)];
        if (i == 0) f.reference = ImageF();
        w.addFrame(i, f);
    }
    EXPECT_ERROR(SequenceReader::open((dir / "manifest").string()), "frame 1 has a \"reference\"");
    fs::remove_all(dir);
}

TEST(Hardening, ExrChannelsAreNeverInventedOrEmpty) {
    const fs::path dir = testing::freshDir("hard", "channels");
    ImageF one(5, 4, 1);
    writeExr((dir / "y.exr").string(), one);
    EXPECT_ERROR(readExr((dir / "y.exr").string(), 3), "expected R,G,B");
    EXPECT_ERROR(readExr((dir / "y.exr").string(), 0), "0 channels");
    EXPECT_EQ(readExr((dir / "y.exr").string(), 1).pixels.size(), 20u);
    fs::remove_all(dir);
}

TEST(Hardening, CommandLineBoundsAreChecked) {
    EXPECT_ERROR(parseFrameRange("0:99999999999", 10), "the sequence has frames 0:10");
    const fs::path dir = testing::freshDir("hard", "eval");
    ASSERT_EQ(
        run("synth -o " + (dir / "in").string() + " --width 16 --height 8 --frames 2 -q").code, 0);
    const std::string base = "eval -r " + (dir / "in").string() + " -m noisy -o " +
                             (dir / "out").string() + " -q --no-flip ";
    // Values out of a flag's own bounds are usage errors (2); a range the input lacks is the
    // input's (1).
    for (const char* bad : {"--crop 1,1,2147483647,1", "--crop 1,1,-2,1", "--zoom -2",
                            "--zoom 2000", "--frames 0:99999999999"}) {
        Result r = run(base + bad);
        const bool input = std::string(bad).rfind("--frames", 0) == 0;
        EXPECT_EQ(r.code, input ? 1 : 2) << bad << ": " << r.output;
        EXPECT_NE(r.output.find(input ? "bmfr: error" : "usage: bmfr eval"), std::string::npos)
            << bad << ": " << r.output;
    }
    fs::remove_all(dir);
}

TEST(Hardening, MethodNamesAreEscapedInTheReport) {
    EXPECT_EQ(escapeHtml("<b>&\"x'"), "&lt;b&gt;&amp;&quot;x&#39;");
}

TEST(Hardening, ResetGivesTheOutputOfANewFilter) {
    const std::vector<FrameData> frames = proceduralFrames(40, 24, 6);
    for (const std::string& name : filterNames()) {
        auto used = makeFilter(name), fresh = makeFilter(name);
        for (int i = 0; i < 3; ++i) used->denoise(frames[size_t(i)].input());
        used->reset();
        for (int i = 3; i < 6; ++i) {
            const ImageView a = used->denoise(frames[size_t(i)].input());
            const ImageView b = fresh->denoise(frames[size_t(i)].input());
            ASSERT_EQ(std::memcmp(a.data, b.data, sizeof(float) * 3 * 40 * 24), 0)
                << name << ", frame " << i;
        }
    }
}

TEST(Hardening, SoakKeepsMemoryFlatAndOutputFinite) {
    for (const std::string& name : filterNames()) {
        Result r = run("soak --filter " + name + " --frames 2000 --size 32x24 --json");
        ASSERT_EQ(r.code, 0) << r.output;
        const nlohmann::json j = nlohmann::json::parse(r.output.substr(r.output.find('{')));
        EXPECT_EQ(j["non_finite_outputs"].get<long long>(), 0) << name;
        // Nothing is allocated after the first frame: RSS may not grow past page-level noise.
        EXPECT_LE(j["rss_end_bytes"].get<long long>() - j["rss_start_bytes"].get<long long>(),
                  256 * 1024)
            << name;
    }
}

// Inputs the fuzzers found stay rejected cleanly (tests/fuzz/corpus/).
TEST(Hardening, FuzzerFindingsAreRejectedCleanly) {
    const fs::path dir = fs::path(BMFR_SOURCE_DIR) / "tests" / "fuzz" / "corpus" / "exr";
    int n = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
        const auto start = std::chrono::steady_clock::now();
        EXPECT_NE(errorOf([&] { readExr(e.path().string(), 3); }), "(no error)") << e.path();
        EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2)) << e.path();
        ++n;
    }
    EXPECT_GT(n, 0);
}

// Round three. A sequence with a frame re-rendered at another size and one cut inside its
// header fails before the first output, in one message that lists both; denoise and eval.
TEST(Hardening, EveryFrameIsCheckedBeforeTheFirstOutput) {
    const fs::path dir = testing::freshDir("hard", "check_first");
    const fs::path seq = dir / "seq";
    ASSERT_EQ(run("synth -o " + seq.string() + " --width 16 --height 8 --frames 6 -q").code, 0);
    writeExr((seq / "color_0003.exr").string(), ImageF(17, 8, 3));
    const std::string albedo = slurp(seq / "albedo_0005.exr");
    std::ofstream(seq / "albedo_0005.exr", std::ios::binary) << albedo.substr(0, 40);
    const fs::path out = dir / "out";
    for (const std::string& args :
         {"denoise " + seq.string() + " -o " + out.string() + " -q --no-flip",
          "eval -r " + seq.string() + " -m noisy -o " + out.string() + " -q --no-flip"}) {
        SCOPED_TRACE(args);
        const Result r = run(args);
        EXPECT_EQ(r.code, 1) << r.output;
        EXPECT_NE(r.output.find("2 of 6 frames cannot be read"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("frame 3 color is 17x8, the sequence is 16x8"), std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("albedo_0005.exr"), std::string::npos) << r.output;
        EXPECT_FALSE(fs::exists(out)) << "a folder was left behind";
    }
}

// A frame whose pixels are cut short (its header intact) fails when it is read, and the error
// says which frames were written.
TEST(Hardening, AFrameBrokenInItsPixelsSaysWhichFramesWereWritten) {
    const fs::path dir = testing::freshDir("hard", "cut_pixels");
    const fs::path seq = dir / "seq", out = dir / "out";
    ASSERT_EQ(run("synth -o " + seq.string() + " --width 16 --height 8 --frames 5 -q").code, 0);
    const std::string color = slurp(seq / "color_0003.exr");
    std::ofstream(seq / "color_0003.exr", std::ios::binary) << color.substr(0, color.size() - 60);
    const Result r = run("denoise " + seq.string() + " -o " + out.string() + " -q --no-flip");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("color_0003.exr"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("frames 0 to 2 were written to " + out.string()), std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(out / "denoised_0002.exr"));
    EXPECT_FALSE(fs::exists(out / "denoised_0003.exr"));
    EXPECT_FALSE(fs::exists(out / "report.json"));
    // Broken at its first frame: nothing written, no folder left.
    const std::string first = slurp(seq / "color_0000.exr");
    std::ofstream(seq / "color_0000.exr", std::ios::binary) << first.substr(0, first.size() - 60);
    const fs::path none = dir / "none";
    const Result r0 = run("denoise " + seq.string() + " -o " + none.string() + " -q --no-flip");
    EXPECT_EQ(r0.code, 1) << r0.output;
    EXPECT_NE(r0.output.find("no frame was written"), std::string::npos) << r0.output;
    EXPECT_FALSE(fs::exists(none));
}

// Numbers are range-checked before they are converted (a conversion out of range is
// undefined behaviour), and a far camera is named as such.
TEST(Hardening, NumbersAreRangeCheckedBeforeConversion) {
    const fs::path dir = testing::freshDir("hard", "numbers");
    ASSERT_EQ(run("synth -o " + dir.string() + " --width 16 --height 8 --frames 1 -q").code, 0);
    nlohmann::json doc = nlohmann::json::parse(slurp(dir / "sequence.json"));
    doc["frames"][0]["aovs"] = {{{"name", "x"}, {"file", "color_0000.exr"}, {"channels", 1e20}}};
    std::ofstream(dir / "sequence.json") << doc.dump();
    auto reader = SequenceReader::open(dir.string());
    reader->setLoadAovs(true);
    FrameData f;
    EXPECT_ERROR(reader->load(0, f), "channels = 1e+20 is outside [1, 3]");
    doc["frames"][0]["jitter"] = {1e300, 0};
    doc["frames"][0].erase("aovs");
    std::ofstream(dir / "sequence.json") << doc.dump();
    EXPECT_ERROR(SequenceReader::open(dir.string())->load(0, f),
                 "jitter must be a finite number that a float holds");
    // Settings: an unsigned seed of -1, an int of 3e9, a float of 1e300.
    EXPECT_ERROR(makeFilter("bmfr", {{"seed", "-1"}}), "seed: '-1' is outside [0, 4294967295]");
    EXPECT_ERROR(makeFilter("svgf", {{"iterations", "3000000000"}}),
                 "'3000000000' is outside [-2147483648, 2147483647]");
    EXPECT_ERROR(makeFilter("bmfr", {{"noiseAmplitude", "1e300"}}),
                 "'1e300' is outside the range of a float");
    render::CameraPose far;
    far.position = {0, 0, 1e30f};
    const std::string why = render::cameraPoseProblem(far);
    EXPECT_NE(why.find("1e+30 units from its target"), std::string::npos) << why;
}

} // namespace
} // namespace bmfr

namespace bmfr {
namespace {

/// Where a frame says its buffers are is checked before any is read: device memory is for the
/// cuda backend alone, a frame's buffers are all in one memory, and a host frame's result never
/// goes to a device view. (No GPU is needed: the views are never dereferenced.)
TEST(Hardening, BufferMemoryIsCheckedBeforeAnythingIsRead) {
    const std::vector<FrameData> frames = proceduralFrames(16, 12, 1);
    auto expectError = [](const std::function<void()>& f, const std::string& what) {
        try {
            f();
            ADD_FAILURE() << "no error; expected: " << what;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
        }
    };
    for (const std::string& name : filterNames()) {
        SCOPED_TRACE(name);
        auto filter = makeFilter(name);
        FrameInput device = frames[0].input();
        for (ImageView* v : {&device.color, &device.albedo, &device.normal, &device.position})
            v->memory = Memory::Cuda;
        expectError([&] { filter->denoise(device); },
                    "the frame's buffers are in CUDA device memory, which the cpu backend cannot "
                    "read: use backend cuda");
        FrameInput mixed = frames[0].input();
        mixed.albedo.memory = Memory::Cuda;
        expectError([&] { filter->denoise(mixed); },
                    "input buffer 'albedo' is in CUDA device memory, colour in host memory");
        std::vector<float> pixels(16 * 12 * 3);
        MutableImageView out{pixels.data(), 16, 12, 3, 0, Memory::Cuda};
        expectError([&] { filter->denoise(frames[0].input(), out); },
                    "output buffer is in CUDA device memory, the frame's buffers in host memory");
        // None of it moved the history: the next frame is a first frame.
        auto fresh = makeFilter(name);
        const ImageView a = filter->denoise(frames[0].input());
        const ImageView b = fresh->denoise(frames[0].input());
        EXPECT_EQ(std::memcmp(a.data, b.data, sizeof(float) * 3 * 16 * 12), 0);
    }
}

} // namespace
} // namespace bmfr
