#include "commands.h"
#include "io/output_folder.h"
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
    std::optional<int> width, height, frames, referenceSpp, bounces, directSpp;
    std::string paths;
    std::optional<uint32_t> seed;
    bool noReference = false, quiet = false, list = false, overwrite = false;
    bool diffuseIndirect = false;
};

} // namespace

int runRender(const RenderJob& job);

namespace {

std::string durationText(double seconds) {
    if (seconds < 90) return fmt::format("about {:.0f} s", seconds);
    if (seconds < 5400) return fmt::format("about {:.0f} min", seconds / 60);
    return fmt::format("about {:.0f} h", seconds / 3600);
}

} // namespace

int runRender(const RenderJob& job) {
    if (job.list) {
        fmt::print("{:<24} {:>10} {:>7} {:>9}  {}\n", "preset", "size", "frames", "ref spp",
                   "estimated time on 2 cores (scales with 1/cores)");
        for (const std::string& n : render::presetNames()) {
            const render::SceneDescription d =
                render::loadSceneDescription(n, job.scenesDir, false);
            fmt::print("{:<24} {:>10} {:>7} {:>9}  {}\n", n,
                       fmt::format("{}x{}", d.width, d.height), d.frames, d.referenceSpp,
                       durationText(render::estimatedRenderSeconds(d)));
        }
        fmt::print("Cheaper: --width 320 --height 180 --frames 16 --reference-spp 256 "
                   "(about 1/{:.0f} of the Sponza cost)\n",
                   1280.0 * 720 * 60 * 4096 / (320.0 * 180 * 16 * 256));
        return 0;
    }
    if (job.output.empty()) throw CLI::RequiredError("--output (the sequence folder to write)");
    render::SceneDescription d = render::loadSceneDescription(job.scene, job.scenesDir);
    if (job.width) d.width = *job.width;
    if (job.height) d.height = *job.height;
    if (job.frames) d.frames = *job.frames;
    if (job.referenceSpp) d.referenceSpp = *job.referenceSpp;
    if (job.noReference) d.referenceSpp = 0;
    if (job.bounces) d.bounces = *job.bounces;
    if (job.seed) d.seed = *job.seed;
    if (job.diffuseIndirect) d.diffuseIndirectOnly = true;
    if (job.paths == "mara") d.factoredDirectSpp = job.directSpp.value_or(16);
    if (job.paths == "bmfr") d.factoredDirectSpp = 0;
    if (job.directSpp && d.factoredDirectSpp == 0)
        throw CLI::ValidationError("--direct-spp", "needs --paths mara");
    render::validate(d);

    gInterrupted = false;
    auto previous = std::signal(SIGINT, onInterrupt);
    if (!job.quiet)
        fmt::print("bmfr render: {} ({}), {}x{}, {} frames, {} bounce(s), reference {} spp -> {} "
                   "({} layout)\n",
                   d.name, d.mesh, d.width, d.height, d.frames, d.bounces, d.referenceSpp,
                   job.output, job.layout);
    if (!job.quiet)
        fmt::print("estimated {} on 2 cores of the CI's kind\n",
                   durationText(render::estimatedRenderSeconds(d)));
    const OutputFolder folder(job.output, invocation());
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
    cmd->add_option("-o,--output", job->output,
                    "output directory (required unless --list-presets)");
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
    cmd->add_flag("--diffuse-indirect-only", job->diffuseIndirect,
                  "colour and reference hold only the diffuse indirect light, no emission (the "
                  "signal WALR's paper filters: to compare filters on it)");
    cmd->add_option("--paths", job->paths,
                    "bmfr (the BMFR paper's 1-spp paths; default) or mara (Mara et al. 2017's "
                    "factored paths: one matte and one glossy path, direct light from "
                    "--direct-spp light samples and the paths' first rays, by multiple "
                    "importance sampling, standing in for their rasterised direct light; also "
                    "writes matte_indirect, glossy_indirect, direct_light, specular_f0, "
                    "surface_roughness, glossy_hit_distance)")
        ->check(CLI::IsMember({"bmfr", "mara"}));
    cmd->add_option("--direct-spp", job->directSpp,
                    "with --paths mara: light samples of the direct light at the first hit, "
                    "[1, 4096] (default 16)")
        ->check(CLI::Range(1, 4096));
    cmd->add_option("--layout", job->layout, "manifest (sequence.json) or bmfr (original dataset)")
        ->default_val("manifest");
    cmd->add_flag("--list-presets", job->list, "print the preset names");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] { exitCode = runRender(*job); });
}

} // namespace bmfr::app
