#include "commands.h"
#include "io/sequence.h"
#include "progress.h"
#include "synth/procedural_scene.h"
#include <filesystem>
#include <fmt/core.h>

namespace bmfr::app {

void addDemoCommand(CLI::App& app, int& exitCode) {
    struct DemoJob {
        std::string output = "bmfr-demo";
        ProceduralSceneOptions scene;
        bool quiet = false;
    };
    auto job = std::make_shared<DemoJob>();
    CLI::App* cmd = app.add_subcommand(
        "demo", "generate the built-in sequence, denoise it, write images and scores");
    cmd->add_option("-o,--output", job->output, "output directory")->default_val("bmfr-demo");
    cmd->add_option("--width", job->scene.width, "pixels")->default_val(640);
    cmd->add_option("--height", job->scene.height, "pixels")->default_val(360);
    cmd->add_option("--frames", job->scene.frames, "frame count")->default_val(30);
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] {
        const std::string input = (std::filesystem::path(job->output) / "input").string();
        ProceduralScene scene(job->scene);
        ManifestWriter writer(input, scene.info());
        Progress progress("generate", job->scene.frames, job->quiet);
        FrameData f;
        for (int i = 0; i < job->scene.frames; ++i) {
            scene.render(i, f);
            writer.addFrame(i, f);
            progress.step(i + 1);
        }
        progress.finish();
        DenoiseJob dj;
        dj.input = input;
        dj.output = (std::filesystem::path(job->output) / "denoised").string();
        dj.quiet = job->quiet;
        dj.debug = true;
        exitCode = runDenoise(dj);
        if (!job->quiet) fmt::print("input (noisy colour, features, truth): {}\n", input);
    });
}

} // namespace bmfr::app
