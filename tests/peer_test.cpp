// `bmfr peer oidn`: Intel Open Image Denoise run as bmfr's filters are, so that `bmfr eval` scores
// it beside them (its frames against OIDN's own binding: tests/python/oidn_against_pyoidn.py).
#include "cli_runner.h"
#include "peers/oidn_library.h"
#include "test_support.h"
#include <filesystem>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;
using bmfr::testing::runCli;
using bmfr::testing::slurp;

fs::path sequence(const std::string& name) {
    return bmfr::testing::synthSequence("peer", name, 40, 24, 3);
}

TEST(Peer, WithoutOidnSaysWhereItLookedAndHowToInstallIt) {
    const fs::path in = sequence("missing"), out = in.string() + "_out";
    const auto r = runCli("peer oidn " + in.string() + " -o " + out.string() +
                          " --oidn-library /nonexistent/libOpenImageDenoise.so.2");
    EXPECT_EQ(r.code, 1) << r.output;
    for (const char* text : {"Intel Open Image Denoise (OIDN) was not found",
                             "/nonexistent/libOpenImageDenoise.so.2:", "scripts/install-oidn.sh"})
        EXPECT_NE(r.output.find(text), std::string::npos) << text << " in: " << r.output;
    EXPECT_FALSE(fs::exists(out)) << "nothing is made when nothing can run";
    // A library that is not OIDN is named as such.
    const auto notOidn =
        runCli("peer oidn " + in.string() + " -o " + out.string() + " --oidn-library libm.so.6");
    EXPECT_EQ(notOidn.code, 1);
    EXPECT_NE(notOidn.output.find("libm.so.6: it has no oidnNewDevice (not OIDN 2)"),
              std::string::npos)
        << notOidn.output;
    fs::remove_all(in);
}

TEST(Peer, MistakesOnItsCommandLineAreUsageErrors) {
    const auto bare = runCli("peer");
    EXPECT_EQ(bare.code, 2) << bare.output;
    EXPECT_NE(bare.output.find("usage: bmfr peer COMMAND"), std::string::npos) << bare.output;
    EXPECT_NE(bare.output.find("bmfr peer needs a command: oidn"), std::string::npos)
        << bare.output;
    const auto unknown = runCli("peer nidon in -o out");
    EXPECT_EQ(unknown.code, 2) << unknown.output;
    const auto twice = runCli("eval -r in -m a -m a -o out");
    EXPECT_EQ(twice.code, 2) << twice.output;
    EXPECT_NE(twice.output.find("two methods are named 'a'"), std::string::npos) << twice.output;
    const auto clash = runCli("eval -r in -m noisy -m oidn=x -o out --oidn");
    EXPECT_EQ(clash.code, 2) << clash.output;
    const auto quality = runCli("peer oidn in -o out --quality ultra");
    EXPECT_EQ(quality.code, 2) << quality.output;
    EXPECT_NE(quality.output.find("usage: bmfr peer oidn INPUT -o OUTPUT"), std::string::npos)
        << quality.output;
    EXPECT_NE(quality.output.find("run 'bmfr peer oidn --help'"), std::string::npos)
        << quality.output;
}

TEST(Peer, OidnWritesWhatDenoiseWritesAndEvalScoresItWithItsTime) {
    const fs::path in = sequence("run"), out = in.string() + "_oidn", eval = in.string() + "_eval";
    if (bmfr::oidn::sanitizerBuild()) {
        const auto r = runCli("peer oidn " + in.string() + " -o " + out.string());
        EXPECT_EQ(r.code, 1);
        EXPECT_TRUE(r.output.find("built with AddressSanitizer") != std::string::npos ||
                    r.output.find("was not found") != std::string::npos)
            << r.output;
        EXPECT_FALSE(fs::exists(out));
        fs::remove_all(in);
        GTEST_SKIP() << "OIDN cannot run under AddressSanitizer";
    }
    ASSERT_TRUE(bmfr::oidn::available())
        << "OIDN is not installed: run scripts/install-oidn.sh (scripts/install-deps.sh does)";
    const auto r = runCli("peer oidn " + in.string() + " -o " + out.string() +
                          " --quality fast --prefilter none --threads 1");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("OIDN 2.5.1, RT filter, CPU device (1 threads), quality fast, "
                            "prefilter none"),
              std::string::npos)
        << r.output;
    for (int i = 0; i < 3; ++i)
        for (const char* ext : {"exr", "png"})
            EXPECT_TRUE(fs::exists(out / ("denoised_000" + std::to_string(i) + "." + ext)));
    EXPECT_TRUE(fs::exists(out / "scores.csv"));
    const auto report = nlohmann::json::parse(slurp(out / "report.json"));
    EXPECT_EQ(report["filter"], "oidn");
    EXPECT_EQ(report["reprojection"], "none (single-frame)");
    EXPECT_EQ(report["settings"]["quality"], "fast");
    EXPECT_GT(report["median_ms"]["filter"].get<double>(), 0.0);
    EXPECT_LT(report["scores"]["rmse"].get<double>(), report["scores"]["noisy_rmse"].get<double>());

    // A second run refuses the first's outputs, as denoise does.
    const auto again = runCli("peer oidn " + in.string() + " -o " + out.string() + " -q");
    EXPECT_EQ(again.code, 1);
    EXPECT_NE(again.output.find("--overwrite"), std::string::npos) << again.output;

    const auto e = runCli("eval -r " + in.string() + " -m noisy -m theirs=" + out.string() +
                          " -o " + eval.string() + " --no-flip");
    ASSERT_EQ(e.code, 0) << e.output;
    EXPECT_NE(e.output.find("theirs = Intel Open Image Denoise, single-frame"), std::string::npos)
        << e.output;
    EXPECT_NE(e.output.find("| ms/frame ↓ |"), std::string::npos) << e.output;
    const auto table = nlohmann::json::parse(slurp(eval / "table.json"));
    EXPECT_EQ(table["methods"]["theirs"]["ms_per_frame"].get<double>(),
              report["median_ms"]["total"].get<double>());
    EXPECT_NE(slurp(eval / "report.html").find("single-frame"), std::string::npos);
    // eval --oidn runs the peer on the reference sequence's input itself.
    const auto own = runCli("eval -r " + in.string() + " -m noisy -o " + eval.string() +
                            "_own --no-flip -q --frames 1:3 --oidn");
    ASSERT_EQ(own.code, 0) << own.output;
    EXPECT_TRUE(fs::exists(fs::path(eval.string() + "_own") / "oidn" / "denoised_0002.exr"));
    EXPECT_FALSE(fs::exists(fs::path(eval.string() + "_own") / "oidn" / "denoised_0000.exr"));
    const auto ownTable =
        nlohmann::json::parse(slurp(fs::path(eval.string() + "_own") / "table.json"));
    EXPECT_GT(ownTable["methods"]["oidn"]["ms_per_frame"].get<double>(), 0.0);
    EXPECT_LT(ownTable["methods"]["oidn"]["mean"]["rmse"].get<double>(),
              ownTable["methods"]["noisy"]["mean"]["rmse"].get<double>());
    fs::remove_all(eval.string() + "_own");
    // A failed eval --oidn (a method that is not there) leaves no folder behind.
    const fs::path failed = eval.string() + "_failed";
    const auto bad = runCli("eval -r " + in.string() + " -m noisy -m gone=" + failed.string() +
                            "_nothing -o " + failed.string() + " --no-flip -q --oidn");
    EXPECT_EQ(bad.code, 1) << bad.output;
    EXPECT_FALSE(fs::exists(failed)) << bad.output;
    for (const fs::path& p : {in, out, eval}) fs::remove_all(p);
}

} // namespace
