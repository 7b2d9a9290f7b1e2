// The bmfr command line: a full run writes what it promises; bad input exits non-zero with a
// message naming the problem.
#include "backend/cuda/cuda_device.h"
#include "cli_runner.h"
#include "io/exr.h"
#include "peers/oidn_library.h"
#include "test_support.h"
#include <array>
#include <bmfr/error.h>
#include <bmfr/filter.h>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;

using Result = bmfr::testing::CliResult;
Result run(const std::string& args) {
    return bmfr::testing::runCli(args);
}

TEST(Cli, SynthThenDenoiseWritesImagesDebugBuffersAndScores) {
    fs::path in = bmfr::testing::scratchPath("cli", "in"),
             out = bmfr::testing::scratchPath("cli", "out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 64 --height 48 --frames 4 -q").code, 0);
    Result r = run("denoise " + in.string() + " -o " + out.string() + " --debug --frames 1:4");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("Scores vs reference"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("fit"), std::string::npos);
    for (const char* f : {"denoised_0001.exr", "denoised_0003.png", "scores.csv", "report.json",
                          "debug/accumulated_0002.exr", "debug/fitted_0002.exr",
                          "debug/history_length_0002.exr", "debug/discard_mask_0002.png"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    EXPECT_FALSE(fs::exists(out / "denoised_0000.exr")); // outside --frames
    // --quiet prints nothing on success.
    Result q = run("denoise " + in.string() + " -o " + out.string() + " -q --no-png --overwrite");
    EXPECT_EQ(q.code, 0);
    EXPECT_EQ(q.output, "");
    fs::remove_all(in);
    fs::remove_all(out);
}

TEST(Cli, OriginalLayoutIsDetected) {
    fs::path in = bmfr::testing::scratchPath("cli", "orig"),
             out = bmfr::testing::scratchPath("cli", "orig_out");
    ASSERT_EQ(
        run("synth -o " + in.string() + " --width 40 --height 30 --frames 3 --layout bmfr -q").code,
        0);
    Result r = run("denoise " + in.string() + " -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("bmfr layout"), std::string::npos) << r.output;
    fs::remove_all(in);
    fs::remove_all(out);
}

TEST(Cli, BadInputExitsNonZeroWithAReason) {
    Result missing = run("denoise /nonexistent/seq -o /tmp/x");
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.output.find("input directory not found: /nonexistent/seq"), std::string::npos)
        << missing.output;

    fs::path in = bmfr::testing::scratchPath("cli", "bad"),
             out = bmfr::testing::scratchPath("cli", "bad_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 32 --height 32 --frames 2 -q").code, 0);
    std::ofstream(in / "normal_0001.exr") << "garbage";
    Result broken = run("denoise " + in.string() + " -o " + out.string() + " -q");
    EXPECT_EQ(broken.code, 1);
    EXPECT_NE(broken.output.find("normal_0001.exr"), std::string::npos) << broken.output;

    Result range = run("denoise " + in.string() + " -o " + out.string() + " --frames 5:9");
    EXPECT_EQ(range.code, 1);
    EXPECT_NE(range.output.find("frames 0:2"), std::string::npos) << range.output;

    Result feature = run("denoise " + in.string() + " -o " + out.string() + " --features 1,x");
    EXPECT_EQ(feature.code, 2); // a flag's value that does not parse is a usage error
    EXPECT_NE(feature.output.find("unknown feature 'x'"), std::string::npos) << feature.output;
    fs::remove_all(in);
    fs::remove_all(out);
}

TEST(Cli, NanInputsGiveOneWarningLine) {
    fs::path in = bmfr::testing::scratchPath("cli", "nan"),
             out = bmfr::testing::scratchPath("cli", "nan_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 32 --height 32 --frames 3 -q").code, 0);
    for (int frame : {1, 2}) {
        const std::string file = (in / ("color_000" + std::to_string(frame) + ".exr")).string();
        bmfr::ImageF color = bmfr::readExr(file, 3);
        color.at(5, 6, 0) = NAN;
        color.at(7, 8, 2) = INFINITY;
        bmfr::writeExr(file, color);
    }
    Result r = run("denoise " + in.string() + " -o " + out.string() + " --no-png");
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string warning =
        "replaced 4 NaN/Inf input values with 0 in 2 frame(s) (first: frame 1)";
    size_t at = r.output.find(warning);
    EXPECT_NE(at, std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("NaN/Inf", at + warning.size()), std::string::npos); // one line
    bmfr::ImageF result = bmfr::readExr((out / "denoised_0002.exr").string(), 3);
    for (float v : result.pixels) ASSERT_TRUE(std::isfinite(v));
    fs::remove_all(in);
    fs::remove_all(out);
}

} // namespace

namespace {

TEST(Cli, EvalWritesTablesPlotsCropsHeatMapsAndAReport) {
    fs::path in = bmfr::testing::scratchPath("cli", "eval_in"),
             den = bmfr::testing::scratchPath("cli", "eval_den"),
             noTaa = bmfr::testing::scratchPath("cli", "eval_notaa"),
             out = bmfr::testing::scratchPath("cli", "eval_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 64 --height 48 --frames 4 -q").code, 0);
    ASSERT_EQ(run("denoise " + in.string() + " -o " + den.string() + " -q --no-png").code, 0);
    ASSERT_EQ(
        run("denoise " + in.string() + " -o " + noTaa.string() + " -q --no-png --disable taa").code,
        0);
    Result r =
        run("eval -r " + in.string() + " -m noisy -m bmfr=" + den.string() +
            " -m \"no taa=" + noTaa.string() + "\" -o " + out.string() + " --crop 10,10,16,12");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("| bmfr |"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("report: " + (out / "report.html").string()), std::string::npos)
        << r.output;
    for (const char* f :
         {"table.md", "table.csv", "table.json", "per_frame.csv", "run.json", "plot_rmse.png",
          "plot_rmse.svg", "plot_ssim.png", "plot_flip.svg", "plot_temporal_error.png",
          "frames.png", "crop_0.png", "heatmap_0.png", "heatmap_2.png", "report.html",
          "viewer/0_reference_0003.png", "viewer/3_no-taa_0000.png"})
        EXPECT_TRUE(fs::exists(out / f)) << f;
    // The report is self-contained: every image inline; files beside it are only linked.
    std::ifstream html(out / "report.html");
    std::string text((std::istreambuf_iterator<char>(html)), {});
    EXPECT_NE(text.find("data:image/png;base64,"), std::string::npos);
    for (size_t at = text.find("src=\""); at != std::string::npos; at = text.find("src=\"", at + 1))
        EXPECT_EQ(text.compare(at + 5, 5, "data:"), 0) << text.substr(at, 60);
    for (const char* external : {"src=\"http", "href=\"http", "url(http", "@import"})
        EXPECT_EQ(text.find(external), std::string::npos) << external;
    EXPECT_NE(text.find("<svg"), std::string::npos);
    // The run section names the command, the machine and each method's settings.
    EXPECT_NE(text.find("bmfr eval"), std::string::npos);
    EXPECT_NE(text.find("hardware threads"), std::string::npos);
    EXPECT_NE(text.find("taa=false"), std::string::npos) << "the no-TAA method's settings";
    // Denoised beats noisy, and the best RMSE is in bold.
    std::ifstream md(out / "table.md");
    std::string table((std::istreambuf_iterator<char>(md)), {});
    EXPECT_EQ(table.find("| noisy | **"), std::string::npos) << table;
    // A crop outside the frame is a clear error.
    Result bad =
        run("eval -r " + in.string() + " -m noisy -o " + out.string() + " --crop 60,40,16,16 -q");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("outside the 64x48 frame"), std::string::npos) << bad.output;
    for (const fs::path& p : {in, den, noTaa, out}) fs::remove_all(p);
}

TEST(Cli, DemoRendersDenoisesEveryWayAndWritesTheReport) {
    const fs::path out = bmfr::testing::scratchPath("cli", "demo");
    const Result r =
        run("demo -o " + out.string() + " --width 48 --height 36 --frames 3 --reference-spp 4 -q");
    ASSERT_EQ(r.code, 0) << r.output;
    std::vector<std::string> folders = {
        "denoised", "accumulation_only", "bmfr_no_taa",   "svgf",
        "walr",     "bmfr_faithful",     "svgf_faithful", "mara2017"};
    // OIDN where it is installed (scripts/install-oidn.sh; never in a sanitizer build).
    if (bmfr::oidn::available()) folders.push_back("oidn");
    for (const std::string& folder : folders)
        EXPECT_TRUE(fs::exists(out / folder / "denoised_0002.exr")) << folder;
    EXPECT_TRUE(fs::exists(out / "report" / "report.html"));
    std::ifstream json(out / "report" / "table.json");
    const std::string table((std::istreambuf_iterator<char>(json)), {});
    for (const char* key : {"\"bmfr faithful\"", "\"svgf faithful\"", "\"mara2017\"",
                            "\"temporal_change_error\"", "\"ms_per_frame\""})
        EXPECT_NE(table.find(key), std::string::npos) << key;
    EXPECT_EQ(table.find("\"oidn\"") != std::string::npos, bmfr::oidn::available());
    // The preset is applied: the faithful output is not the default one's.
    EXPECT_NE(bmfr::readExr((out / "denoised" / "denoised_0002.exr").string(), 3).pixels,
              bmfr::readExr((out / "bmfr_faithful" / "denoised_0002.exr").string(), 3).pixels);
    fs::remove_all(out);
}

TEST(Cli, AblateRunsStagesAndTheGreedyFeatureStudy) {
    fs::path in = bmfr::testing::scratchPath("cli", "ablate_in"),
             out = bmfr::testing::scratchPath("cli", "ablate_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 48 --height 32 --frames 3 -q").code, 0);
    Result r = run("ablate " + in.string() + " -o " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    for (const char* s : {"without fitting (phase II)", "without TAA", "without taaSameSurface",
                          "## Greedy feature selection", "+ normals", "+ material_id"})
        EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
    EXPECT_TRUE(fs::exists(out / "ablation.json"));
    EXPECT_TRUE(fs::exists(out / "plot_greedy_rmse.png"));
    // The default (quality) run sets each value to the faithful preset's in turn, beside
    // flipping its switches; the faithful run has no values to set back.
    for (const char* s :
         {"without secondGrid", "blockSize 32 (faithful)", "emitterRatio 16 (faithful)"})
        EXPECT_NE(r.output.find(s), std::string::npos) << s << "\n" << r.output;
    fs::remove_all(out);
    Result f = run("ablate " + in.string() + " -o " + out.string() + " --preset faithful");
    ASSERT_EQ(f.code, 0) << f.output;
    EXPECT_NE(f.output.find("with taaSameSurface"), std::string::npos) << f.output;
    EXPECT_EQ(f.output.find("(faithful)"), std::string::npos) << f.output;
    fs::remove_all(in);
    fs::remove_all(out);
}

} // namespace

namespace {

TEST(Cli, DenoiseWithSvgfAndFewerThanOneSample) {
    fs::path in = bmfr::testing::scratchPath("cli", "svgf_in"),
             out = bmfr::testing::scratchPath("cli", "svgf_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 64 --height 48 --frames 3 -q").code, 0);
    Result r = run("denoise " + in.string() + " -o " + out.string() +
                   " --filter svgf --sample-fraction 0.5 --no-png");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("bmfr denoise (svgf, cpu backend)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("atrous"), std::string::npos) << r.output;
    EXPECT_TRUE(fs::exists(out / "denoised_0002.exr"));
    Result bad = run("denoise " + in.string() + " -o " + out.string() + " --filter nlm");
    EXPECT_EQ(bad.code, 2); // a usage error
    EXPECT_NE(bad.output.find("--filter: 'nlm' is not one of bmfr, svgf"), std::string::npos)
        << bad.output;
    fs::remove_all(in);
    fs::remove_all(out);
}

TEST(Cli, MovingObjectsRenderWithMotionAndDenoiseSaysHowItReprojects) {
    fs::path in = bmfr::testing::scratchPath("cli", "objects_in"),
             out = bmfr::testing::scratchPath("cli", "objects_out"),
             cam = bmfr::testing::scratchPath("cli", "objects_cam");
    ASSERT_EQ(run("render -s cornell-objects --width 40 --height 30 --frames 3 --no-reference -q "
                  "-o " +
                  in.string())
                  .code,
              0);
    for (const char* f :
         {"motion_0002.exr", "previous_position_0002.exr", "previous_normal_0002.exr"})
        EXPECT_TRUE(fs::exists(in / f)) << f;
    Result with = run("denoise " + in.string() + " -o " + out.string() + " --no-png");
    ASSERT_EQ(with.code, 0) << with.output;
    EXPECT_NE(with.output.find("reprojection: motion vectors"), std::string::npos) << with.output;
    Result without =
        run("denoise " + in.string() + " -o " + cam.string() + " --no-png --no-motion");
    ASSERT_EQ(without.code, 0) << without.output;
    EXPECT_NE(without.output.find("motion vectors ignored: --no-motion"), std::string::npos);
    const bmfr::ImageF a = bmfr::readExr((out / "denoised_0002.exr").string(), 3),
                       b = bmfr::readExr((cam / "denoised_0002.exr").string(), 3);
    EXPECT_NE(a.pixels, b.pixels) << "the moving objects reproject differently";
    std::ifstream report(out / "report.json");
    const std::string text((std::istreambuf_iterator<char>(report)), {});
    EXPECT_NE(text.find("\"reprojection\": \"motion vectors\""), std::string::npos) << text;
    for (const fs::path& p : {in, out, cam}) fs::remove_all(p);
}

TEST(Cli, WalrFiltersTheColourOrTheRenderedDiffuseIndirectLight) {
    fs::path in = bmfr::testing::scratchPath("cli", "walr_in"),
             out = bmfr::testing::scratchPath("cli", "walr_out"),
             synth = bmfr::testing::scratchPath("cli", "walr_synth");
    ASSERT_EQ(run("render -s cornell-moving --width 40 --height 30 --frames 2 --no-reference -q "
                  "-o " +
                  in.string())
                  .code,
              0);
    EXPECT_TRUE(fs::exists(in / "diffuse_indirect_0001.exr"));
    EXPECT_EQ(bmfr::readExr((in / "motion_0001.exr").string(), 3).channels, 3); // depth offset
    for (const char* signal : {"color", "diffuse-indirect"}) {
        Result r = run("denoise " + in.string() + " -o " + out.string() +
                       " --no-png --overwrite --filter walr --walr-signal " + signal);
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("bmfr denoise (walr, cpu backend)"), std::string::npos) << r.output;
        EXPECT_NE(r.output.find("spatial"), std::string::npos) << r.output;
    }
    // A sequence without the buffer that diffuse-indirect mode filters: an error that names it.
    ASSERT_EQ(run("synth -o " + synth.string() + " --width 32 --height 24 --frames 2 -q").code, 0);
    Result bad = run("denoise " + synth.string() + " -o " + out.string() +
                     " --no-png --overwrite --filter walr --walr-signal diffuse-indirect");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.output.find("'diffuseIndirect' is missing"), std::string::npos) << bad.output;
    for (const fs::path& p : {in, out, synth}) fs::remove_all(p);
}

TEST(Cli, Mara2017FiltersTheFactoredPathsOrWarnsOnceWithoutThem) {
    fs::path in = bmfr::testing::scratchPath("cli", "mara_in"),
             out = bmfr::testing::scratchPath("cli", "mara_out"),
             plain = bmfr::testing::scratchPath("cli", "mara_plain");
    Result rendered = run("render -s cornell-moving --width 40 --height 30 --frames 2 "
                          "--no-reference -q --paths mara --direct-spp 4 -o " +
                          in.string());
    ASSERT_EQ(rendered.code, 0) << rendered.output;
    for (const char* stem : {"matte_indirect", "glossy_indirect", "direct_light", "specular_f0",
                             "surface_roughness", "glossy_hit_distance"})
        EXPECT_TRUE(fs::exists(in / (std::string(stem) + "_0001.exr"))) << stem;
    const std::string warning = "has no matte_indirect";
    Result r =
        run("denoise " + in.string() + " -o " + out.string() + " --no-png --filter mara2017");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("bmfr denoise (mara2017, cpu backend)"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("glossy bilateral"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(warning), std::string::npos) << r.output;
    // Our own paths: the documented fallback, said once.
    ASSERT_EQ(
        run("render -s cornell-moving --width 40 --height 30 --frames 3 --no-reference -q -o " +
            plain.string())
            .code,
        0);
    Result fallback = run("denoise " + plain.string() + " -o " + out.string() +
                          " --no-png -q --overwrite --filter mara2017");
    ASSERT_EQ(fallback.code, 0) << fallback.output;
    const size_t at = fallback.output.find(warning);
    EXPECT_NE(at, std::string::npos) << fallback.output;
    EXPECT_EQ(fallback.output.find(warning, at + 1), std::string::npos) << fallback.output;
    Result bad = run("render -s cornell-moving --width 8 --height 8 --frames 1 --no-reference -q "
                     "--direct-spp 4 -o " +
                     (plain / "x").string());
    EXPECT_EQ(bad.code, 2) << bad.output; // a usage error
    EXPECT_NE(bad.output.find("--paths mara"), std::string::npos) << bad.output;
    for (const fs::path& p : {in, out, plain}) fs::remove_all(p);
}

TEST(Cli, SettingsComeFromTheFilterTablesAndAreChecked) {
    fs::path in = bmfr::testing::scratchPath("cli", "set_in"),
             out = bmfr::testing::scratchPath("cli", "set_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 40 --height 24 --frames 2 -q").code, 0);
    const std::string base =
        "denoise " + in.string() + " -o " + out.string() + " -q --no-png --overwrite ";
    EXPECT_EQ(run(base + "--set blockSize=16 --backend reference --disable fitting").code, 0);
    EXPECT_EQ(run(base + "--filter svgf --svgf-iterations 3 --svgf-reverse-levels").code, 0);
    struct Bad {
        const char* args;
        const char* message;
    };
    for (const Bad& b :
         {Bad{"--backend gpu", "unknown backend 'gpu'"},
          Bad{"--svgf-iterations 3", "--svgf-iterations is not a setting of the bmfr"},
          Bad{"--set nope=1", "'nope' is not a setting of the bmfr filter"},
          Bad{"--set blockSize", "expected KEY=VALUE"},
          Bad{"--block-size 65", "--block-size 65 is outside [8, 64]"},
          Bad{"--set blockSize=7", "--block-size 7 is outside [8, 64]"},
          Bad{"--block-size 1e", "--block-size 1e is not a number"},
          Bad{"--taa maybe", "--taa maybe is not true or false"},
          Bad{"--disable fitting --filter svgf", "--disable fitting: not a switch of the svgf"}}) {
        Result r = run(base + b.args);
        EXPECT_EQ(r.code, 2) << b.args; // values typed on the command line: usage errors
        EXPECT_NE(r.output.find(b.message), std::string::npos) << b.args << ": " << r.output;
    }
    fs::remove_all(in);
    fs::remove_all(out);
}

// Without a GPU (or without CUDA in the build), the cuda backend is one clear error, exit 1;
// with one, it denoises as the CPU backend does.
TEST(Cli, CudaBackendDenoisesOrSaysWhyNot) {
    fs::path in = bmfr::testing::scratchPath("cli", "cuda_in"),
             out = bmfr::testing::scratchPath("cli", "cuda_out");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 40 --height 24 --frames 2 -q").code, 0);
    bool device = true;
    try {
        bmfr::cuda::requireDevice();
    } catch (const bmfr::Error&) {
        device = false;
    }
    for (const char* filter : {"bmfr", "svgf"}) {
        Result r = run("denoise " + in.string() + " -o " + out.string() +
                       " -q --no-png --backend cuda --filter " + filter);
        if (device) {
            EXPECT_EQ(r.code, 0) << filter << ": " << r.output;
        } else {
            EXPECT_EQ(r.code, 1) << filter;
            EXPECT_NE(r.output.find("no CUDA device: "), std::string::npos) << r.output;
        }
    }
    fs::remove_all(in);
    fs::remove_all(out);
}

TEST(Cli, SettingsDocTableIsTheGeneratedOne) {
    Result r = run("settings --markdown");
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream doc(std::string(BMFR_SOURCE_DIR) + "/docs/settings.md");
    ASSERT_TRUE(doc) << "docs/settings.md is missing";
    std::stringstream ss;
    ss << doc.rdbuf();
    const std::string text = ss.str(), begin = "<!-- settings-table:begin",
                      end = "<!-- settings-table:end";
    const size_t a = text.find(begin), b = text.find(end);
    ASSERT_NE(a, std::string::npos);
    ASSERT_NE(b, std::string::npos);
    const size_t first = text.find('\n', a) + 1;
    EXPECT_EQ(text.substr(first, b - first), r.output)
        << "docs/settings.md's settings table is stale: run `bash scripts/update-settings-doc.sh` "
           "(it pastes `bmfr settings --markdown` between the markers)";
}

} // namespace

namespace {

std::vector<float> pixelsOf(const fs::path& p) {
    const bmfr::ImageF image = bmfr::readExr(p.string(), 3);
    return {image.pixels.begin(), image.pixels.end()};
}

TEST(Cli, QualityIsTheDefaultAndFaithfulSetsThePapersValuesBack) {
    // The library's list: the faithful preset sets back what the defaults improve on.
    using bmfr::presetSettings, bmfr::SettingValues;
    // In the settings table's order.
    EXPECT_EQ(presetSettings("bmfr", "faithful"), (SettingValues{{"taaSameSurface", "false"},
                                                                 {"taaRangeCompressed", "false"},
                                                                 {"taaMotionWeight", "false"},
                                                                 {"blockSize", "32"},
                                                                 {"noiseAmplitude", "0.01"},
                                                                 {"secondBlendAlpha", "0.1"},
                                                                 {"excludeEmitters", "false"},
                                                                 {"clampFireflies", "false"},
                                                                 {"secondGrid", "false"},
                                                                 {"visibilityFeature", "false"},
                                                                 {"visibilityTaps", "false"},
                                                                 {"adaptiveHistory", "false"},
                                                                 {"emitterRatio", "16"}}));
    EXPECT_EQ(presetSettings("svgf", "faithful"), (SettingValues{{"taaSameSurface", "false"},
                                                                 {"taaRangeCompressed", "false"},
                                                                 {"taaMotionWeight", "false"}}));
    EXPECT_TRUE(presetSettings("bmfr", "quality").empty());
    EXPECT_THROW(presetSettings("bmfr", "fast"), bmfr::Error);
    Result listed = run("settings bmfr --preset faithful");
    ASSERT_EQ(listed.code, 0) << listed.output;
    EXPECT_NE(listed.output.find(
                  "bmfr: taaSameSurface=false taaRangeCompressed=false taaMotionWeight=false "
                  "blockSize=32 "
                  "noiseAmplitude=0.01 secondBlendAlpha=0.1 excludeEmitters=false "
                  "clampFireflies=false secondGrid=false visibilityFeature=false "
                  "visibilityTaps=false adaptiveHistory=false emitterRatio=16"),
              std::string::npos)
        << listed.output;
    // On the command line: --preset faithful gives the bits of its values set by hand, and
    // --preset quality those of no flags; a flag after the preset overrides it.
    fs::path in = bmfr::testing::scratchPath("cli", "preset_in");
    ASSERT_EQ(run("synth -o " + in.string() + " --width 40 --height 30 --frames 4 -q").code, 0);
    auto denoise = [&](const std::string& name, const std::string& flags) {
        const fs::path out = bmfr::testing::scratchPath("cli", "preset_" + name);
        const Result r = run("denoise " + in.string() + " -o " + out.string() + " -q " + flags);
        EXPECT_EQ(r.code, 0) << r.output;
        return pixelsOf(out / "denoised_0003.exr");
    };
    const std::vector<float> faithful = denoise("faithful", "--preset faithful"),
                             byFlag = denoise(
                                 "flag",
                                 "--taa-same-surface false --taa-range-compressed false "
                                 "--taa-motion-weight false "
                                 "--exclude-emitters false --second-grid false "
                                 "--clamp-fireflies false --visibility-feature false "
                                 "--visibility-taps false --block-size 32 --emitter-ratio 16 "
                                 "--adaptive-history false --alpha2 0.1 --noise 0.01"),
                             quality = denoise("quality", "--preset quality"),
                             plain = denoise("plain", ""),
                             overridden = denoise(
                                 "override",
                                 "--preset faithful --taa-same-surface --taa-range-compressed "
                                 "--taa-motion-weight --exclude-emitters --second-grid "
                                 "--clamp-fireflies --visibility-feature "
                                 "--visibility-taps --block-size 16 --emitter-ratio 4 "
                                 "--adaptive-history --alpha2 0.08 --noise 0.005");
    ASSERT_FALSE(faithful.empty());
    EXPECT_EQ(faithful, byFlag);
    EXPECT_EQ(quality, plain);
    EXPECT_EQ(overridden, plain);
    EXPECT_NE(faithful, plain);
    EXPECT_NE(run("denoise " + in.string() + " -o " +
                  bmfr::testing::scratchPath("cli", "preset_bad").string() + " --preset fast")
                  .code,
              0);
    fs::remove_all(in);
}

} // namespace
