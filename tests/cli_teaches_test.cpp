// A CLI that teaches: each mistake a new user made has a message in the CLI's words (never a
// library's), a "did you mean" where a name was mistyped, and the exit code of its kind (2 for
// the command line, 1 for the input).
#include "cli_runner.h"
#include "test_support.h"
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;
using bmfr::testing::runCli;

/// A 3-frame synthetic sequence with references, made once per test.
fs::path sequence(const std::string& name) {
    return bmfr::testing::synthSequence("teaches", name, 32, 24, 3);
}

/// No parser's or JSON library's own wording reaches the user.
void expectNoLibraryWords(const std::string& output) {
    for (const char* raw : {"The following argument", "json.exception", " not in {",
                            "Could not convert", "is not an allowed value"})
        EXPECT_EQ(output.find(raw), std::string::npos) << raw << " in: " << output;
}

struct Expect {
    const char* args; ///< after "denoise IN -o OUT"
    int code;
    const char* message;
};

TEST(CliTeaches, MistypedNamesAreUsageErrorsThatSuggestTheNearestName) {
    const fs::path in = sequence("names"), out = in.string() + "_out";
    const std::string io = "denoise " + in.string() + " -o " + out.string() + " -q ";
    for (const Expect& e : {
             Expect{"16 --blocksize", 2,
                    "unknown option '--blocksize' (did you mean '--block-size'?)"},
             Expect{"--blok-size=32", 2,
                    "unknown option '--blok-size' (did you mean '--block-size'?)"},
             Expect{"--set blocksize=16", 2,
                    "'blocksize' is not a setting of the bmfr filter (did you mean 'blockSize'?)"},
             Expect{"--set nosuchkey=1", 2, "(`bmfr settings bmfr` lists them)"},
             Expect{"--filter svfg", 2,
                    "--filter: 'svfg' is not one of bmfr, svgf, walr, mara2017 "
                    "(did you mean 'svgf'?)"},
             Expect{"--filter oidn", 2,
                    "--filter: 'oidn' is not one of bmfr, svgf, walr, mara2017"},
             Expect{"--preset fast", 2, "--preset: 'fast' is not one of quality, faithful"},
             Expect{"--preset qualty", 2, "(did you mean 'quality'?)"},
             Expect{"--disable taaa", 2,
                    "--disable taaa: not a switch of the bmfr filter (did you "
                    "mean 'taa'?)"},
         }) {
        const auto r = runCli(io + e.args);
        EXPECT_EQ(r.code, e.code) << e.args << ": " << r.output;
        EXPECT_NE(r.output.find(e.message), std::string::npos) << e.args << ": " << r.output;
        EXPECT_NE(r.output.find("usage: bmfr denoise INPUT -o OUTPUT"), std::string::npos)
            << e.args << ": " << r.output;
        expectNoLibraryWords(r.output);
        EXPECT_FALSE(fs::exists(out)) << e.args << ": a usage error writes nothing";
    }
    const auto c = runCli("denoize " + in.string());
    EXPECT_EQ(c.code, 2);
    EXPECT_NE(c.output.find("unknown command 'denoize' (did you mean 'denoise'?)"),
              std::string::npos)
        << c.output;
    for (const char* other : {"bench --filter oidn", "soak --filter oidn", "settings oidn",
                              "bench --baseline-filter oidn"}) {
        const auto r = runCli(other);
        EXPECT_EQ(r.code, 2) << other << ": " << r.output;
        EXPECT_NE(r.output.find("'oidn' is not one of"), std::string::npos) << r.output;
    }
    // Other commands' values out of their bounds or lists are usage errors too.
    for (const char* other :
         {"soak --backend cdua", "bench --set blok=3 --sizes 16x16", "render -o x --width 0",
          "synth -o x --frames 0", "eval -r x -m noisy -o y --log-plots maybe",
          "tonemap a.exr -o a.exr"}) {
        const auto r = runCli(other);
        EXPECT_EQ(r.code, 2) << other << ": " << r.output;
        expectNoLibraryWords(r.output);
    }
}

TEST(CliTeaches, SettingErrorsNameTheFlagAndExit2) {
    const fs::path in = sequence("settings"), out = in.string() + "_out";
    const std::string io = "denoise " + in.string() + " -o " + out.string() + " -q ";
    for (const Expect& e : {
             Expect{"--block-size 33", 2, "bmfr: --block-size 33 must be even"},
             Expect{"--block-size 7", 2, "bmfr: --block-size 7 is outside [8, 64]"},
             Expect{"--set blockSize=33", 2, "bmfr: --block-size 33 must be even"},
             Expect{"--filter walr --set edgeFar=0.001", 2,
                    "--walr-edge-far 0.001 must exceed edgeNear"},
             Expect{"--frames x", 2, "frame range expects A:B, A: or :B, got 'x'"},
             Expect{"--sample-fraction abc", 2, "--sample-fraction abc: not a valid value"},
             Expect{"--taa-same-surface maybe", 2, "--taa-same-surface maybe is not true or false"},
             // `iterations` is a key of SVGF and WALR: the flag named is the chosen filter's.
             Expect{"--filter walr --walr-iterations 999", 2, "--walr-iterations 999 is outside"},
             Expect{"--filter walr --set edgeNear=0.9", 2, "must exceed edgeNear (0.9)"},
             Expect{"--features n.x,n.y", 2, "--features n.x,n.y must begin with the constant 1"},
             Expect{"--frames 2:1", 2, "frame range 2:1 is empty"},
             Expect{"--frames 0:9", 1, "frame range 0:9: the sequence has frames 0:3"},
             Expect{"-o other", 2, "--output is given more than once"},
             Expect{"--backend gpu", 2, "--backend gpu: unknown backend 'gpu'"},
         }) {
        const auto r = runCli(io + e.args);
        EXPECT_EQ(r.code, e.code) << e.args << ": " << r.output;
        EXPECT_NE(r.output.find(e.message), std::string::npos) << e.args << ": " << r.output;
        expectNoLibraryWords(r.output);
    }
    const std::string bare = "denoise " + in.string() + " -o " + out.string();
    for (const Expect& e : {
             Expect{"--quiet=maybe", 2,
                    "--quiet maybe: not a valid value (true or false is expected)"},
             Expect{"-- extra", 2, "unexpected argument 'extra'"},
         }) {
        const auto r = runCli(bare + " " + e.args);
        EXPECT_EQ(r.code, e.code) << e.args << ": " << r.output;
        EXPECT_NE(r.output.find(e.message), std::string::npos) << e.args << ": " << r.output;
    }
}

TEST(CliTeaches, AMissingCameraMatrixIsNamedInPlainWords) {
    const fs::path in = sequence("camera");
    nlohmann::json j = nlohmann::json::parse(bmfr::testing::slurp(in / "sequence.json"));
    j["frames"][1].erase("view_projection");
    std::ofstream(in / "sequence.json") << j.dump();
    const auto r = runCli("denoise " + in.string() + " -o " + in.string() + "_out -q");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("sequence.json frame 1: \"view_projection\" is missing"),
              std::string::npos)
        << r.output;
    expectNoLibraryWords(r.output);
}

TEST(CliTeaches, AFolderOfPicturesSaysWhatTheInputMustBe) {
    const fs::path in = bmfr::testing::freshDir("teaches", "pngs");
    for (const char* name : {"frame_0000.png", "frame_0001.png"}) std::ofstream(in / name) << "x";
    const auto r = runCli("denoise " + in.string() + " -o " + in.string() + "_out -q");
    EXPECT_EQ(r.code, 1) << r.output;
    for (const char* needle :
         {"it holds 2 .png files: display images, not linear radiance",
          "linear EXR frames with noise-free features", "docs/input-layouts.md"})
        EXPECT_NE(r.output.find(needle), std::string::npos) << needle << ": " << r.output;
}

TEST(CliTeaches, DenoiseRefusesAnEarlierRunsOutputsUnlessOverwrite) {
    const fs::path in = sequence("rerun"), out = bmfr::testing::scratchPath("teaches", "rerun_out");
    const std::string io = "denoise " + in.string() + " -o " + out.string() + " -q --no-flip";
    ASSERT_EQ(runCli(io).code, 0);
    ASSERT_TRUE(fs::exists(out / "denoised_0002.exr"));
    std::ofstream(out / "notes.txt") << "the user's own file";
    const std::string before = bmfr::testing::slurp(out / "report.json");

    // A shorter second run would leave frame 2 beside scores that do not cover it.
    const auto refused = runCli(io + " --frames 0:2");
    EXPECT_EQ(refused.code, 1) << refused.output;
    EXPECT_NE(refused.output.find("holds the outputs of an earlier run"), std::string::npos)
        << refused.output;
    EXPECT_NE(refused.output.find("--overwrite"), std::string::npos) << refused.output;
    EXPECT_EQ(bmfr::testing::slurp(out / "report.json"), before) << "a refusal changes nothing";

    // A file that only looks like an output is the user's: a frame name without its number.
    std::ofstream(out / "denoised_final.png") << "the user's picture";
    const auto ours = nlohmann::json::parse(before);

    const auto replaced = runCli(io + " --frames 0:2 --overwrite");
    EXPECT_EQ(replaced.code, 0) << replaced.output;
    EXPECT_TRUE(fs::exists(out / "denoised_0001.exr"));
    EXPECT_FALSE(fs::exists(out / "denoised_0002.exr")) << "no stale frame is left";
    EXPECT_EQ(nlohmann::json::parse(bmfr::testing::slurp(out / "report.json"))["frames"], 2);
    EXPECT_TRUE(fs::exists(out / "notes.txt")) << "only the earlier run's outputs are removed";
    EXPECT_TRUE(fs::exists(out / "denoised_final.png"));
    EXPECT_TRUE(ours.contains("median_ms")) << "what marks a report as a denoise run's";

    // A folder whose report.json is not a denoise run's is refused all the same (the run would
    // replace that file), and the file is left alone.
    const fs::path mixed = bmfr::testing::scratchPath("teaches", "rerun_mixed");
    fs::create_directories(mixed);
    std::ofstream(mixed / "report.json") << R"({"tool": "another"})";
    std::ofstream(mixed / "scores.csv") << "a,b\n1,2\n";
    const auto intoMixed = runCli("denoise " + in.string() + " -o " + mixed.string() +
                                  " -q --no-flip --no-png --frames 0:1");
    EXPECT_EQ(intoMixed.code, 1) << intoMixed.output; // its report.json would be replaced
    EXPECT_NE(intoMixed.output.find("report.json"), std::string::npos) << intoMixed.output;
    EXPECT_EQ(bmfr::testing::slurp(mixed / "report.json"), R"({"tool": "another"})");
}

TEST(CliTeaches, AFailedRunSaysWhatItLeft) {
    const fs::path in = sequence("failed"), out = in.string() + "_out";
    // Frame 0's colour is cut short after its header: the run fails on its first frame.
    const fs::path color = in / "color_0000.exr";
    const std::string bytes = bmfr::testing::slurp(color);
    std::ofstream(color, std::ios::binary | std::ios::trunc) << bytes.substr(0, bytes.size() / 2);
    const auto r = runCli("denoise " + in.string() + " -o " + out.string() + " -q --debug");
    EXPECT_EQ(r.code, 1) << r.output;
    // The header is whole, so the file passes the check of every frame and fails on its pixels.
    EXPECT_NE(r.output.find("no frame was written (" + out.string() + " is removed)"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(out)) << "a run that wrote nothing leaves no folder";
}

TEST(CliTeaches, RenderWithNoSceneOrSizeIsQuickAndAnHourNeedsYes) {
    const fs::path out = bmfr::testing::scratchPath("teaches", "render");
    // Days on any machine: refused before anything is written, with the way on.
    const auto full = runCli("render -o " + out.string() +
                             " -s cornell-moving --width 4096 --height 4096 --frames 1000");
    EXPECT_EQ(full.code, 2) << full.output;
    EXPECT_NE(full.output.find("add --yes to start it"), std::string::npos) << full.output;
    EXPECT_FALSE(fs::exists(out));

    // No scene and no size: the quick size (the reference is skipped to keep the test short).
    const auto quick = runCli("render -o " + out.string() + " --no-reference");
    ASSERT_EQ(quick.code, 0) << quick.output;
    EXPECT_NE(quick.output.find("a quick render: no scene or size was given"), std::string::npos)
        << quick.output;
    EXPECT_NE(quick.output.find("640x480, 60 frames, reference 4096 spp"), std::string::npos)
        << quick.output;
    const nlohmann::json seq = nlohmann::json::parse(bmfr::testing::slurp(out / "sequence.json"));
    EXPECT_EQ(seq["width"], 256);
    EXPECT_EQ(seq["height"], 192);
    EXPECT_EQ(seq["frames"].size(), 24u);
}

TEST(CliTeaches, DenoiseHelpOpensWithUsageExamplesAndTheInput) {
    const auto r = runCli("denoise --help");
    EXPECT_EQ(r.code, 0);
    EXPECT_EQ(r.output.rfind("usage: bmfr denoise INPUT -o OUTPUT [options]", 0), 0u) << r.output;
    // In this order: examples, the input format, the command's options, the settings every
    // filter has, then the chosen filter's own (bmfr by default) and where the others' are.
    size_t at = 0;
    for (const char* part :
         {"examples:", "bmfr denoise ", "input:", "required per frame:", "\nOptions:", "--preset",
          "\nSettings of every filter:", "\nBMFR settings (--filter bmfr):", "--block-size",
          "The other filters' settings (svgf, walr, mara2017): bmfr denoise "
          "--filter NAME --help"}) {
        const size_t found = r.output.find(part, at);
        ASSERT_NE(found, std::string::npos) << part << " after offset " << at << ":\n" << r.output;
        at = found;
    }
    EXPECT_EQ(r.output.find("--svgf-iterations"), std::string::npos) << "one filter at a time";
    // A switch reads as one: no "=true" beside "default false".
    EXPECT_EQ(r.output.find("[BOOL]=true"), std::string::npos);
    EXPECT_NE(r.output.find("--taa-same-surface[=true|false]"), std::string::npos);

    const auto svgf = runCli("denoise --filter svgf --help");
    EXPECT_EQ(svgf.code, 0);
    EXPECT_NE(svgf.output.find("\nSVGF settings (--filter svgf):"), std::string::npos);
    EXPECT_NE(svgf.output.find("--svgf-iterations"), std::string::npos) << svgf.output;
    EXPECT_EQ(svgf.output.find("--block-size"), std::string::npos) << svgf.output;
}

} // namespace
