// Runs the bmfr CLI built beside the tests and captures its exit code and output.
#pragma once
#include "test_support.h"
#include <array>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>

namespace bmfr::testing {

struct CliResult {
    int code;
    std::string output; ///< stdout and stderr together (or stdout alone when asked)
};

/// `bmfr ARGS`; with `stdoutOnly` stderr goes to /dev/null; `env` ("NAME=value ...") is set
/// for the command alone.
inline CliResult runCli(const std::string& args, bool stdoutOnly = false,
                        const std::string& env = "") {
    const std::string cmd = (env.empty() ? "" : "env " + env + " ") + std::string(BMFR_CLI_PATH) +
                            " " + args + (stdoutOnly ? " 2>/dev/null" : " 2>&1");
    FILE* p = popen(cmd.c_str(), "r");
    std::string out;
    std::array<char, 512> buf;
    while (fgets(buf.data(), int(buf.size()), p)) out += buf.data();
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

/// A synthetic sequence with references (`bmfr synth`) in a scratch folder of its own.
inline std::filesystem::path synthSequence(const std::string& suite, const std::string& name,
                                           int width, int height, int frames) {
    const std::filesystem::path p = scratchPath(suite, name);
    const CliResult r =
        runCli("synth -o " + p.string() + " --width " + std::to_string(width) + " --height " +
               std::to_string(height) + " --frames " + std::to_string(frames) + " -q");
    EXPECT_EQ(r.code, 0) << r.output;
    return p;
}

} // namespace bmfr::testing
