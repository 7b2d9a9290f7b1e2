// The command line's conventions: exit codes (0 ok, 1 runtime error, 2 usage error), the
// command list, -q everywhere, -o for every output, errors in flag terms, --version, --json,
// progress lines in logs, and the original-layout header that the authors' code compiles.
#include "cli_runner.h"
#include "test_support.h"
#include <bmfr/version.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using bmfr::testing::runCli;

const char* const kCommands[] = {"demo",  "render", "denoise", "eval",     "ablate",
                                 "bench", "synth",  "tonemap", "settings", "soak"};

using bmfr::testing::slurp;

TEST(CliConventions, NoCommandOrAnUnknownOneListsTheCommandsAndExits2) {
    for (const char* args : {"", "frob"}) {
        const auto r = runCli(args);
        EXPECT_EQ(r.code, 2) << args;
        EXPECT_EQ(r.output.rfind("bmfr: ", 0), 0u) << r.output;
        for (const char* c : kCommands)
            EXPECT_NE(r.output.find(std::string("  ") + c + " "), std::string::npos) << c;
    }
    EXPECT_NE(runCli("frob").output.find("unknown command 'frob'"), std::string::npos);
}

TEST(CliConventions, UsageErrorsExit2WithThePrefixAndTheUsageLine) {
    struct Case {
        const char* args;
        const char* needle;
    };
    for (const Case& c : {Case{"denoise", "usage: bmfr denoise INPUT -o OUTPUT"},
                          Case{"denoise in", "usage: bmfr denoise INPUT -o OUTPUT"},
                          Case{"denoise in -o out --no-such-flag", "no-such-flag"},
                          Case{"bench --frames many", "usage: bmfr bench"},
                          Case{"render", "--output"}, Case{"eval -o x", "usage: bmfr eval"}}) {
        const auto r = runCli(c.args);
        EXPECT_EQ(r.code, 2) << c.args << ": " << r.output; // never CLI11's 104..114
        EXPECT_EQ(r.output.rfind("bmfr: ", 0), 0u) << c.args << ": " << r.output;
        EXPECT_NE(r.output.find(c.needle), std::string::npos) << c.args << ": " << r.output;
    }
}

TEST(CliConventions, VersionNamesTheVersionCommitAndBackends) {
    const auto r = runCli("--version");
    EXPECT_EQ(r.code, 0);
    EXPECT_NE(r.output.find(std::string("bmfr ") + BMFR_VERSION + " (commit "), std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("backends: reference, cpu"), std::string::npos) << r.output;
    // With the cuda backend built: its device, or why there is none.
    if (r.output.find("backends: reference, cpu, cuda") != std::string::npos) {
        EXPECT_TRUE(r.output.find("; cuda device: ") != std::string::npos ||
                    r.output.find("; cuda: no CUDA device: ") != std::string::npos)
            << r.output;
    }
}

TEST(CliConventions, CpuPathIsNamedAndChosenByTheEnvironment) {
    auto r = runCli("--version");
    EXPECT_NE(r.output.find("cpu path: "), std::string::npos) << r.output;
    r = runCli("--version", false, "BMFR_CPU_ISA=baseline");
    EXPECT_NE(r.output.find("cpu path: baseline of "), std::string::npos) << r.output;
    r = runCli("bench --sizes 64x48 --frames 2 --warmup 1 --no-baseline -q", false,
               "BMFR_CPU_ISA=baseline");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("(baseline path, half history)"), std::string::npos) << r.output;
    // A name that is not a path is an error that lists the accepted ones, never a fallback.
    r = runCli("bench --sizes 64x48 --frames 2 --warmup 1 --no-baseline -q", false,
               "BMFR_CPU_ISA=avx3");
    EXPECT_EQ(r.code, 1) << r.output;
    EXPECT_NE(r.output.find("unknown CPU path 'avx3' (use baseline, avx2 or avx512)"),
              std::string::npos)
        << r.output;
}

TEST(CliConventions, BenchTimesEveryFilterInOneTable) {
    auto r = runCli("bench --filters all --sizes 48x32 --frames 2 --warmup 1 --json -q", true);
    ASSERT_EQ(r.code, 0) << r.output;
    const nlohmann::json j = nlohmann::json::parse(r.output)["48x32"];
    for (const char* f : {"bmfr", "svgf", "walr", "mara2017"}) {
        ASSERT_TRUE(j["filters"].contains(f)) << r.output;
        EXPECT_GT(j["filters"][f]["total_ms"].get<double>(), 0.0) << f;
        EXPECT_GT(j["filters"][f]["x_floor"].get<double>(), 0.0) << f;
    }
    EXPECT_DOUBLE_EQ(j["filters"]["bmfr"]["x_bmfr"].get<double>(), 1.0);
    EXPECT_GT(j["single_pass_floor_ms"].get<double>(), 0.0);
    r = runCli("bench --filters bmfr,walr --sizes 48x32 --frames 1 --warmup 0 -q");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("x bmfr"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("\n  walr "), std::string::npos) << r.output;
    EXPECT_EQ(runCli("bench --filters all --filter bmfr --sizes 48x32 --frames 1").code, 2);
    EXPECT_EQ(runCli("bench --filters bmfr,oidn").code, 2);
    // --set reaches every timed filter that has the key (walr's iterations are at most 5), and
    // a key none of them has, or a baseline option, is an error rather than silently ignored.
    const std::string tiny = " --sizes 48x32 --frames 1 --warmup 0 -q";
    r = runCli("bench --filters bmfr,walr --set iterations=9" + tiny);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("--walr-iterations 9 is outside"), std::string::npos) << r.output;
    r = runCli("bench --filters bmfr,svgf --set finalTap=25" + tiny);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("'finalTap' is not a setting of bmfr, svgf"), std::string::npos)
        << r.output;
    r = runCli("bench --filters walr,mara2017 --set finalTap=25" + tiny);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_NE(r.output.find("did you mean 'finalTaps'"), std::string::npos) << r.output;
    EXPECT_EQ(runCli("bench --filters bmfr,walr --set iterations" + tiny).code, 2);
    for (const char* baseline :
         {"--baseline-set blockSize=16", "--baseline-filter walr", "--no-baseline",
          "--baseline-backend cpu", "--baseline-preset faithful"})
        EXPECT_EQ(runCli("bench --filters all " + std::string(baseline) + tiny).code, 2)
            << baseline;
    // A key reaches every filter that has it, a flag name only its own: SVGF's iterations are
    // [1, 8], WALR's [0, 5] (0 = by size).
    EXPECT_EQ(runCli("bench --filters svgf,walr --set iterations=0" + tiny).code, 2);
    EXPECT_EQ(runCli("bench --filters svgf,walr --set walr-iterations=0" + tiny).code, 0);
    EXPECT_EQ(runCli("bench --filters svgf,mara2017 --set finalTaps=25" + tiny).code, 0);
}

TEST(CliConventions, EveryCommandTakesQuietAndWritesWithDashO) {
    for (const char* c : kCommands) {
        const auto help = runCli(std::string(c) + " --help");
        EXPECT_EQ(help.code, 0) << c;
        EXPECT_NE(help.output.find("-q, --quiet"), std::string::npos) << c;
        // An output is given with -o everywhere, never as a positional argument.
        EXPECT_EQ(help.output.find("\n  output "), std::string::npos) << c << help.output;
    }
    for (const char* c : {"demo", "render", "denoise", "eval", "ablate", "synth", "tonemap"})
        EXPECT_NE(runCli(std::string(c) + " --help").output.find("-o, --output"), std::string::npos)
            << c;
}

TEST(CliConventions, DenoiseRefusesToWriteIntoItsInputAndLeavesItAlone) {
    const fs::path in = bmfr::testing::scratchPath("conv", "self");
    ASSERT_EQ(runCli("synth -o " + in.string() + " --width 16 --height 8 --frames 2 -q").code, 0);
    const std::string before = slurp(in / "sequence.json");
    const size_t files = size_t(std::distance(fs::directory_iterator(in), {}));
    for (const std::string& out : {in.string(), in.string() + "/", in.string() + "/."}) {
        const auto r = runCli("denoise " + in.string() + " -o " + out + " -q");
        EXPECT_EQ(r.code, 2) << out; // the command line names one folder twice
        EXPECT_NE(r.output.find("is the input folder"), std::string::npos) << r.output;
    }
    EXPECT_EQ(slurp(in / "sequence.json"), before);
    EXPECT_EQ(size_t(std::distance(fs::directory_iterator(in), {})), files);
    fs::remove_all(in);
}

TEST(CliConventions, ScoresAreLabelledWithTheFilterAndEvalPrintsJson) {
    const fs::path in = bmfr::testing::scratchPath("conv", "json_in"),
                   den = bmfr::testing::scratchPath("conv", "json_den"),
                   out = bmfr::testing::scratchPath("conv", "json_out");
    ASSERT_EQ(runCli("synth -o " + in.string() + " --width 32 --height 24 --frames 3 -q").code, 0);
    const auto d = runCli("denoise " + in.string() + " -o " + den.string() + " --filter svgf " +
                          "--no-png --no-flip");
    ASSERT_EQ(d.code, 0) << d.output;
    EXPECT_NE(d.output.find("\n  svgf "), std::string::npos) << d.output;
    EXPECT_EQ(d.output.find("\n  bmfr "), std::string::npos) << d.output;
    const auto e = runCli("eval -r " + in.string() + " -m noisy -m svgf=" + den.string() + " -o " +
                              out.string() + " --no-flip --json",
                          true);
    ASSERT_EQ(e.code, 0);
    const nlohmann::json j = nlohmann::json::parse(e.output); // stdout is the JSON alone
    EXPECT_TRUE(j["methods"].contains("svgf"));
    EXPECT_LT(j["methods"]["svgf"]["mean"]["rmse"].get<double>(),
              j["methods"]["noisy"]["mean"]["rmse"].get<double>());
    EXPECT_EQ(nlohmann::json::parse(slurp(out / "table.json")), j);
    for (const fs::path& p : {in, den, out}) fs::remove_all(p);
}

TEST(CliConventions, LogsGetLinesNotCarriageReturnsAndHearFromLongSteps) {
    const fs::path in = bmfr::testing::scratchPath("conv", "log_in"),
                   out = bmfr::testing::scratchPath("conv", "log_out"),
                   r = bmfr::testing::scratchPath("conv", "log_r");
    ASSERT_EQ(runCli("synth -o " + in.string() + " --width 32 --height 32 --frames 2 -q").code, 0);
    // Output is a pipe here, not a terminal.
    const auto a = runCli("ablate " + in.string() + " -o " + out.string());
    ASSERT_EQ(a.code, 0) << a.output;
    EXPECT_EQ(a.output.find('\r'), std::string::npos);
    EXPECT_NE(a.output.find("ablate: configuration 1 ("), std::string::npos) << a.output;
    // One render frame that outlasts the heartbeat interval prints a still-working line.
    setenv("BMFR_PROGRESS_HEARTBEAT_MS", "200", 1);
    const auto g = runCli("render -o " + r.string() +
                          " --width 96 --height 64 --frames 1 --reference-spp 512");
    unsetenv("BMFR_PROGRESS_HEARTBEAT_MS");
    ASSERT_EQ(g.code, 0) << g.output;
    EXPECT_NE(g.output.find("render: 0/1, working ("), std::string::npos) << g.output;
    EXPECT_EQ(g.output.find('\r'), std::string::npos);
    for (const fs::path& p : {in, out, r}) fs::remove_all(p);
}

TEST(CliConventions, TheOriginalLayoutHeaderCompilesWithTheSystemCompiler) {
    const fs::path in = bmfr::testing::scratchPath("conv", "header");
    ASSERT_EQ(
        runCli("synth -o " + in.string() + " --width 16 --height 8 --frames 3 --layout bmfr -q")
            .code,
        0);
    // The authors' code #includes camera_matrices.h; so does this program, which prints a value.
    std::ofstream(in / "use_header.cpp")
        << "#include \"camera_matrices.h\"\n#include <cstdio>\n"
           "int main() { std::printf(\"%zu %g %g\\n\", sizeof(camera_matrices) / "
           "sizeof(camera_matrices[0]), double(camera_matrices[1][3][3]), "
           "double(position_limit_squared)); return 0; }\n";
    const std::string cxx = std::getenv("CXX") ? std::getenv("CXX") : "c++";
    const std::string exe = (in / "use_header").string();
    ASSERT_EQ(std::system((cxx + " -std=c++11 -Wall -Werror -o " + exe + " " +
                           (in / "use_header.cpp").string())
                              .c_str()),
              0)
        << slurp(in / "camera_matrices.h");
    FILE* p = popen(exe.c_str(), "r");
    char line[128] = {};
    ASSERT_TRUE(fgets(line, sizeof line, p));
    pclose(p);
    EXPECT_EQ(std::string(line).rfind("3 ", 0), 0u) << line;
    fs::remove_all(in);
}

} // namespace
