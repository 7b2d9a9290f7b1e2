#include "commands.h"
#include "progress.h"
#include "render/sequence_renderer.h"
#include <atomic>
#include <bmfr/error.h>
#include <csignal>
#include <fmt/core.h>

namespace bmfr::app {

namespace {

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) {
    gInterrupted = true;
}

struct RenderJob {
    std::string output, scene = "cornell-moving", scenesDir = "../shared/scenes",
                        layout = "manifest";
    std::optional<int> width, height, frames, referenceSpp, bounces;
    std::optional<uint32_t> seed;
    bool noReference = false, quiet = false, list = false, overwrite = false;
};

} // namespace

int runRender(const RenderJob& job);

int runRender(const RenderJob& job) {
    if (job.list) {
        for (const std::string& n : render::presetNames()) fmt::print("{}\n", n);
        return 0;
    }
    if (job.output.empty()) throw Error("render: an output directory is required");
    render::SceneDescription d = render::loadSceneDescription(job.scene, job.scenesDir);
    if (job.width) d.width = *job.width;
    if (job.height) d.height = *job.height;
    if (job.frames) d.frames = *job.frames;
    if (job.referenceSpp) d.referenceSpp = *job.referenceSpp;
    if (job.noReference) d.referenceSpp = 0;
    if (job.bounces) d.bounces = *job.bounces;
    if (job.seed) d.seed = *job.seed;
    render::validate(d);

    gInterrupted = false;
    auto previous = std::signal(SIGINT, onInterrupt);
    if (!job.quiet)
        fmt::print("bmfr render: {} ({}), {}x{}, {} frames, {} bounce(s), reference {} spp -> {} "
                   "({} layout)\n",
                   d.name, d.mesh, d.width, d.height, d.frames, d.bounces, d.referenceSpp,
                   job.output, job.layout);
    Progress progress("render", d.frames, job.quiet);
    render::SequenceRenderOptions o{job.output, job.layout, job.quiet, job.overwrite};
    render::SequenceRenderReport r = render::renderSequence(
        d, o, &gInterrupted, [&](int done, int) { progress.step(done); },
        [&](const std::string& w) { fmt::print(stderr, "bmfr: warning: {}\n", w); });
    progress.finish();
    std::signal(SIGINT, previous);
    const double seconds = r.inputSeconds + r.referenceSeconds;
    if (!job.quiet) {
        fmt::print("{} triangles (load + BVH {:.2f} s); rendered {} frame(s), {} already on disk\n",
                   r.triangles, r.loadSeconds, r.rendered, r.skipped);
        if (r.rendered)
            fmt::print("1-spp input {:.3f} s/frame, reference {:.2f} s/frame, {:.2f} Mrays/s\n",
                       r.inputSeconds / r.rendered, r.referenceSeconds / r.rendered,
                       seconds > 0 ? double(r.rays) / seconds * 1e-6 : 0.0);
    }
    if (r.interrupted) {
        fmt::print(stderr,
                   "bmfr: interrupted; {} complete frame(s) kept; run the same command to resume\n",
                   r.rendered + r.skipped);
        return 130;
    }
    return 0;
}

void addRenderCommand(CLI::App& app, int& exitCode) {
    auto job = std::make_shared<RenderJob>();
    CLI::App* cmd =
        app.add_subcommand("render", "path trace a sequence: 1-spp input, features, reference");
    cmd->add_option("output", job->output, "output directory");
    cmd->add_option("-s,--scene", job->scene, "preset name or scene description JSON")
        ->default_val("cornell-moving");
    cmd->add_option("--scenes", job->scenesDir, "folder holding sponza/ (for the presets)")
        ->default_val("../shared/scenes");
    cmd->add_option("--width", job->width, "pixels");
    cmd->add_option("--height", job->height, "pixels");
    cmd->add_option("--frames", job->frames, "frame count");
    cmd->add_option("--reference-spp", job->referenceSpp,
                    "reference samples per pixel (default 4096)");
    cmd->add_flag("--no-reference", job->noReference, "skip the reference");
    cmd->add_flag("--overwrite", job->overwrite,
                  "replace a folder holding another scene's sequence (or one bmfr did not "
                  "render) instead of refusing it");
    cmd->add_option("--bounces", job->bounces,
                    "BSDF-sampled secondary rays per path (default 1, as the paper)");
    cmd->add_option("--seed", job->seed, "random seed");
    cmd->add_option("--layout", job->layout, "manifest (sequence.json) or bmfr (original dataset)")
        ->default_val("manifest");
    cmd->add_flag("--list-presets", job->list, "print the preset names");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] { exitCode = runRender(*job); });
}

} // namespace bmfr::app
