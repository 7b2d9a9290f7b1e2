// Runs the bmfr CLI built beside the tests and captures its exit code and output.
#pragma once
#include <array>
#include <cstdio>
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

} // namespace bmfr::testing
