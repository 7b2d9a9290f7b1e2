#include "commands.h"
#include "io/exr.h"
#include "io/png.h"

namespace bmfr::app {

void addTonemapCommand(CLI::App& app, int& exitCode) {
    struct Job {
        std::string input, output;
        float exposure = 1.0f;
    };
    auto job = std::make_shared<Job>();
    CLI::App* cmd = app.add_subcommand(
        "tonemap", "write an EXR as a viewable PNG: clamp((x * exposure)^(1/2.2), 0, 1)");
    cmd->add_option("input", job->input, "EXR file")->required();
    cmd->add_option("output", job->output, "PNG file")->required();
    cmd->add_option("--exposure", job->exposure, "linear scale applied first")->default_val(1.0);
    cmd->callback([job, &exitCode] {
        writePngToneMapped(job->output, readExr(job->input, 3), job->exposure);
        exitCode = 0;
    });
}

} // namespace bmfr::app
