// bmfr: denoise 1-spp path-traced sequences with BMFR; benchmark; demo on a built-in scene.
#include "commands.h"
#include <bmfr/error.h>
#include <cstdio>

int main(int argc, char** argv) {
    CLI::App app{"bmfr: real-time reconstruction of 1-spp path-traced sequences "
                 "(Blockwise Multi-Order Feature Regression, Koskela et al. 2019)"};
    app.require_subcommand(1);
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
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const bmfr::Error& e) {
        std::fprintf(stderr, "bmfr: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bmfr: error: %s\n", e.what());
        return 1;
    }
    return exitCode;
}
