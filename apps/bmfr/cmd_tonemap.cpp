#include "commands.h"
#include "io/exr.h"
#include "io/png.h"
#include "usage.h"
#include <bmfr/error.h>
#include <cmath>
#include <filesystem>

namespace bmfr::app {

void addTonemapCommand(CLI::App& app, int& exitCode) {
    struct Job {
        std::string input, output, layer;
        float exposure = 1.0f;
        bool quiet = false;
    };
    auto job = std::make_shared<Job>();
    CLI::App* cmd = app.add_subcommand(
        "tonemap", "write an EXR as a viewable PNG: clamp((x * exposure)^(1/2.2), 0, 1)");
    cmd->add_option("input", job->input, "EXR file")->required();
    cmd->add_option("-o,--output", job->output, "PNG file")->required();
    cmd->add_option("--exposure", job->exposure, "linear scale applied first")->default_val(1.0);
    cmd->add_option("--layer", job->layer,
                    "layer of a multilayer EXR, as \"ViewLayer.Noisy Image\" (default: the plain "
                    "channels, else the Combined pass)");
    cmd->add_flag("-q,--quiet", job->quiet, "accepted on every command; tonemap prints nothing");
    cmd->callback([job, &exitCode] {
        std::error_code ec;
        if (job->output == job->input || std::filesystem::equivalent(job->input, job->output, ec))
            throw UsageError("tonemap: the output " + job->output +
                             " is the input; refusing to overwrite it");
        if (!(std::isfinite(job->exposure) && job->exposure > 0.0f))
            throw UsageError("tonemap: --exposure must be a positive number");
        const std::string layer = job->layer.empty() ? imageLayer(job->input) : job->layer;
        writePngToneMapped(job->output, readExr(job->input, 3, layer), job->exposure);
        exitCode = 0;
    });
}

} // namespace bmfr::app
