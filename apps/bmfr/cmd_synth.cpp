#include "commands.h"
#include "io/output_folder.h"
#include "io/sequence.h"
#include "progress.h"
#include "render/scene_description.h"
#include "synth/procedural_scene.h"
#include "usage.h"
#include <bmfr/error.h>
#include <fmt/core.h>

namespace bmfr::app {

namespace {

struct SynthJob {
    std::string output, layout = "manifest";
    ProceduralSceneOptions scene;
    bool quiet = false;
};

void writeProcedural(const SynthJob& job) {
    ProceduralScene scene(job.scene);
    const OutputFolder folder(job.output, invocation());
    Progress progress("synth", job.scene.frames, job.quiet);
    if (job.layout == "bmfr") {
        std::vector<FrameData> frames(size_t(job.scene.frames));
        for (int i = 0; i < job.scene.frames; ++i)
            scene.render(i, frames[size_t(i)]), progress.step(i + 1);
        writeBmfrLayout(job.output, frames, 0.01f, 1.0f);
    } else if (job.layout == "manifest") {
        ManifestWriter writer(job.output, scene.info());
        FrameData f;
        for (int i = 0; i < job.scene.frames; ++i) {
            scene.render(i, f);
            writer.addFrame(i, f);
            progress.step(i + 1);
        }
    } else {
        throw UsageError("--layout must be manifest or bmfr");
    }
    progress.finish();
    if (!job.quiet)
        fmt::print("wrote {} frames {}x{} ({} layout) to {}\n", job.scene.frames, job.scene.width,
                   job.scene.height, job.layout, job.output);
}

} // namespace

void addSynthCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<SynthJob>();
    CLI::App* cmd = app.add_subcommand(
        "synth", "write the built-in procedural sequence (noisy input, features, exact truth)");
    cmd->add_option("-o,--output", job->output, "output directory")->required();
    cmd->add_option("--width", job->scene.width, "pixels")
        ->check(integerIn(1, render::kMaxSceneSide))
        ->default_val(640);
    cmd->add_option("--height", job->scene.height, "pixels")
        ->check(integerIn(1, render::kMaxSceneSide))
        ->default_val(360);
    cmd->add_option("--frames", job->scene.frames, "frame count")
        ->check(integerIn(1, render::kMaxSceneFrames))
        ->default_val(30);
    cmd->add_option("--seed", job->scene.seed, "noise seed")->default_val(1);
    cmd->add_option("--camera-speed", job->scene.cameraSpeed, "0 = static camera")
        ->default_val(1.0);
    cmd->add_option("--layout", job->layout, "manifest (sequence.json) or bmfr (original dataset)")
        ->check(oneOf({"manifest", "bmfr"}))
        ->default_val("manifest");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] {
        writeProcedural(*job);
        exitCode = 0;
    });
}

} // namespace bmfr::app
