// bmfr: denoise 1-spp path-traced sequences with BMFR; benchmark; demo on a built-in scene.
// Exit codes: 0 success, 1 a runtime error, 2 a usage error, 130 interrupted.
#include "backend/cpu/isa.h"
#include "backend/cuda/cuda_device.h"
#include "commands.h"
#include "core/closest_name.h"
#include "git_commit.h"
#include "help_format.h"
#include "io/shell_quote.h"
#include "usage.h"
#include <algorithm>
#include <bmfr/bmfr.hpp>
#include <cstdio>
#include <fmt/format.h>

namespace {
std::string gInvocation;
} // namespace

namespace bmfr::app {

std::string versionText() {
    std::string path;
    try {
        path = bmfr::cpu::isaName(bmfr::cpu::activeIsa());
    } catch (const bmfr::Error&) {
        path = "none (BMFR_CPU_ISA is invalid)";
    }
    // Which GPU the cuda backend would use, or why none.
    std::string gpu;
    if (bmfr::cuda::built()) {
        try {
            gpu = "; cuda device: " + bmfr::cuda::deviceName();
        } catch (const bmfr::Error& e) {
            gpu = std::string("; cuda: ") + e.what();
        }
    }
    return fmt::format("bmfr {} (commit {}; backends: {}; cpu path: {} of {}{})", BMFR_VERSION,
                       BMFR_GIT_COMMIT, fmt::join(bmfr::compiledBackends(), ", "), path,
                       bmfr::cpu::isaName(bmfr::cpu::bestIsa()), gpu);
}

const std::string& invocation() {
    return gInvocation;
}

} // namespace bmfr::app

using bmfr::app::versionText;

int main(int argc, char** argv) {
    for (int i = 0; i < argc; ++i) gInvocation += (i ? " " : "") + bmfr::shellQuote(argv[i]);
    CLI::App app{"bmfr: real-time reconstruction of 1-spp path-traced sequences "
                 "(Blockwise Multi-Order Feature Regression, Koskela et al. 2019)",
                 "bmfr"};
    app.formatter(std::make_shared<bmfr::app::HelpFormatter>());
    app.set_version_flag("--version", versionText());
    int exitCode = 0;
    bmfr::app::addDemoCommand(app, exitCode);
    bmfr::app::addRenderCommand(app, exitCode);
    bmfr::app::addDenoiseCommand(app, exitCode);
    bmfr::app::addEvalCommand(app, exitCode);
    bmfr::app::addAblateCommand(app, exitCode);
    bmfr::app::addBenchCommand(app, exitCode);
    bmfr::app::addSynthCommand(app, exitCode);
    bmfr::app::addTonemapCommand(app, exitCode);
    bmfr::app::addSettingsCommand(app, exitCode);
    bmfr::app::addSoakCommand(app, exitCode);
    bmfr::app::addPeerCommand(app, exitCode);
    bmfr::app::addBatchCommand(app, exitCode);
    std::vector<std::string> commands;
    for (const CLI::App* sub : app.get_subcommands({})) commands.push_back(sub->get_name());
    const bool known =
        argc > 1 && std::find(commands.begin(), commands.end(), argv[1]) != commands.end();
    if (argc > 1 && argv[1][0] != '-' && !known) {
        std::fprintf(stderr, "bmfr: unknown command '%s'%s\nusage: bmfr COMMAND [options]\n%s",
                     argv[1], bmfr::didYouMean(argv[1], commands).c_str(),
                     bmfr::app::commandList(app).c_str());
        return 2;
    }
    try {
        app.parse(argc, argv);
        if (app.get_subcommands().empty()) {
            std::fprintf(stderr, "bmfr: a command is needed\n%s",
                         bmfr::app::commandList(app).c_str());
            return 2;
        }
    } catch (const CLI::CallForVersion&) {
        std::printf("%s\n", versionText().c_str());
        return 0;
    } catch (const CLI::Success& e) { // --help
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        return bmfr::app::reportUsageError(app, e);
    } catch (const bmfr::app::UsageError& e) {
        return bmfr::app::reportUsageError(app, e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bmfr: error: %s\n", e.what());
        return 1;
    }
    return exitCode;
}
