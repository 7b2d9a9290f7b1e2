#include "commands.h"
#include "io/output_folder.h"
#include "progress.h"
#include "render/sequence_renderer.h"
#include "usage.h"
#include <algorithm>
#include <atomic>
#include <bmfr/error.h>
#include <csignal>
#include <fmt/core.h>
#include <tbb/global_control.h>
#include <thread>

namespace bmfr::app {

namespace {

std::atomic<bool> gInterrupted{false};
extern "C" void onInterrupt(int) {
    gInterrupted = true;
}

struct RenderJob {
    std::string output, scenesDir = "../shared/scenes", layout = "manifest";
    std::optional<std::string> scene;
    std::optional<int> width, height, frames, referenceSpp, bounces, directSpp;
    std::string paths, jitter;
    std::optional<uint32_t> seed;
    std::optional<std::string> frameRange;
    int threads = 0;
    bool noReference = false, quiet = false, list = false, overwrite = false, yes = false;
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

/// "A:B" as frames [A, B) of a sequence of `frames`.
std::pair<int, int> parseFrameRange(const std::string& text, int frames) {
    const size_t colon = text.find(':');
    int a = -1, b = -1;
    try {
        size_t used = 0;
        if (colon != std::string::npos) a = std::stoi(text.substr(0, colon), &used);
        if (colon != std::string::npos && used == colon) {
            b = std::stoi(text.substr(colon + 1), &used);
            if (used != text.size() - colon - 1) b = -1;
        }
    } catch (const std::exception&) {
        a = b = -1;
    }
    if (a < 0 || b <= a || b > frames)
        throw CLI::ValidationError("--frame-range",
                                   fmt::format("'{}' is not A:B with 0 <= A < B <= {} (the frame "
                                               "count); it renders frames A to B-1",
                                               text, frames));
    return {a, b};
}

/// A render over this long needs --yes: a typo in a size should not start a day's work.
constexpr double kLongRenderSeconds = 3600;

/// With no scene and no size, `bmfr render -o OUT` renders the built-in box small enough to
/// finish in about a minute on 2 cores, not the preset's full size.
void applyQuickSize(render::SceneDescription& d) {
    d.width = 256;
    d.height = 192;
    d.frames = 24;
    d.referenceSpp = 128;
}

/// The cores the estimate divides by (estimatedRenderSeconds is for 2; a machine that does not
/// say counts as 2).
unsigned coresHere() {
    return std::max(2u, std::thread::hardware_concurrency());
}

double estimatedHere(const render::SceneDescription& d) {
    return render::estimatedRenderSeconds(d) * 2.0 / coresHere();
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
    const bool quick = !job.scene && !job.width && !job.height && !job.frames && !job.referenceSpp;
    render::SceneDescription d =
        render::loadSceneDescription(job.scene.value_or("cornell-moving"), job.scenesDir);
    const render::SceneDescription full = d;
    if (quick) applyQuickSize(d);
    if (job.width) d.width = *job.width;
    if (job.height) d.height = *job.height;
    if (job.frames) d.frames = *job.frames;
    if (job.referenceSpp) d.referenceSpp = *job.referenceSpp;
    if (job.noReference) d.referenceSpp = 0;
    if (job.bounces) d.bounces = *job.bounces;
    if (job.seed) d.seed = *job.seed;
    if (!job.jitter.empty()) d.jitter = job.jitter == "on";
    if (job.diffuseIndirect) d.diffuseIndirectOnly = true;
    if (job.paths == "mara") d.factoredDirectSpp = job.directSpp.value_or(16);
    if (job.paths == "bmfr") d.factoredDirectSpp = 0;
    if (job.directSpp && d.factoredDirectSpp == 0)
        throw CLI::ValidationError("--direct-spp", "needs --paths mara");
    render::validate(d);
    std::optional<std::pair<int, int>> range;
    if (job.frameRange) {
        if (job.layout != "manifest")
            throw CLI::ValidationError("--frame-range", "needs the manifest layout");
        range = parseFrameRange(*job.frameRange, d.frames);
    }
    const int partFrames = range ? range->second - range->first : d.frames;
    std::optional<tbb::global_control> threadCap;
    if (job.threads > 0)
        threadCap.emplace(tbb::global_control::max_allowed_parallelism, size_t(job.threads));
    double estimate = estimatedHere(d) * partFrames / d.frames;
    if (job.threads > 0)
        estimate *= double(coresHere()) / std::min(unsigned(job.threads), coresHere());
    if (estimate > kLongRenderSeconds && !job.yes)
        throw UsageError(fmt::format(
            "this render is estimated at {} here ({}x{}, {} frames, reference {} spp); add "
            "--yes to start it, or make it cheaper with --width, --height, --frames and "
            "--reference-spp (see --list-presets)",
            durationText(estimate), d.width, d.height, d.frames, d.referenceSpp));

    gInterrupted = false;
    auto previous = std::signal(SIGINT, onInterrupt);
    if (!job.quiet)
        fmt::print("bmfr render: {} ({}), {}x{}, {} frames, {} bounce(s), reference {} spp -> {} "
                   "({} layout)\n",
                   d.name, d.mesh, d.width, d.height, d.frames, d.bounces, d.referenceSpp,
                   job.output, job.layout);
    if (range && !job.quiet)
        fmt::print("part: frames {} to {} of {}; sequence.json is written once all {} are in\n",
                   range->first, range->second - 1, d.frames, d.frames);
    if (!job.quiet)
        fmt::print("estimated {} on {} cores\n", durationText(estimate),
                   job.threads > 0 ? std::min(unsigned(job.threads), coresHere()) : coresHere());
    if (quick && !job.quiet)
        fmt::print("a quick render: no scene or size was given. The preset's full size is "
                   "{}x{}, {} frames, reference {} spp ({}); ask for it with -s {} (and --yes), "
                   "or for any size with --width, --height, --frames and --reference-spp; "
                   "--list-presets lists the scenes\n",
                   full.width, full.height, full.frames, full.referenceSpp,
                   durationText(estimatedHere(full)), d.name);
    // Parts lock apart: they write different frames of one folder at once.
    const OutputFolder folder(
        job.output, invocation(),
        range ? fmt::format("{}.frames-{}-{}", kOutputLockFile, range->first, range->second)
              : std::string(kOutputLockFile));
    Progress progress("render", partFrames, job.quiet);
    render::SequenceRenderOptions o{job.output, job.layout, job.quiet, job.overwrite};
    if (range) {
        o.firstFrame = range->first;
        o.endFrame = range->second;
    }
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
        if (range && !r.interrupted)
            fmt::print("{} of {} frames of the sequence are in{}\n", r.framesIn, d.frames,
                       r.complete ? "; sequence.json written" : "");
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
    cmd->add_option("-s,--scene", job->scene,
                    "preset name or scene description JSON (default cornell-moving; with no "
                    "scene and no size, a quick 256x192, 24-frame, 128-spp render of it)");
    cmd->add_option("--scenes", job->scenesDir, "folder holding sponza/ (for the presets)")
        ->default_val("../shared/scenes");
    cmd->add_option("--width", job->width, "pixels")->check(integerIn(1, render::kMaxSceneSide));
    cmd->add_option("--height", job->height, "pixels")->check(integerIn(1, render::kMaxSceneSide));
    cmd->add_option("--frames", job->frames, "frame count")
        ->check(integerIn(1, render::kMaxSceneFrames));
    cmd->add_option("--reference-spp", job->referenceSpp,
                    "reference samples per pixel (default: the scene's; 4096 for the presets)")
        ->check(integerIn(0, 1 << 20));
    cmd->add_flag("--no-reference", job->noReference, "skip the reference");
    cmd->add_option("--frame-range", job->frameRange,
                    "A:B renders frames A to B-1 only, into the same folder as the other parts "
                    "(which may render at once, on other machines); sequence.json is written by "
                    "the part that completes the sequence (manifest layout)");
    cmd->add_option("--threads", job->threads, "worker threads, 0 = all cores")
        ->check(integerIn(0, 4096))
        ->default_val(0);
    cmd->add_flag("--overwrite", job->overwrite,
                  "replace a folder holding another scene's sequence (or one bmfr did not "
                  "render) instead of refusing it");
    cmd->add_option("--bounces", job->bounces,
                    "BSDF-sampled secondary rays per path (default 1, as the paper)")
        ->check(integerIn(0, 64));
    cmd->add_option("--seed", job->seed, "random seed");
    cmd->add_option("--jitter", job->jitter,
                    "on: each frame's camera moves by a sub-pixel offset (Halton 2,3; the "
                    "default); off: every frame samples its pixels' centres, as an engine "
                    "without TAA jitter renders")
        ->check(CLI::IsMember({"on", "off"}));
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
        ->check(oneOf({"bmfr", "mara"}));
    cmd->add_option("--direct-spp", job->directSpp,
                    "with --paths mara: light samples of the direct light at the first hit, "
                    "[1, 4096] (default 16)")
        ->check(integerIn(1, 4096));
    cmd->add_option("--layout", job->layout, "manifest (sequence.json) or bmfr (original dataset)")
        ->check(oneOf({"manifest", "bmfr"}))
        ->default_val("manifest");
    cmd->add_flag("--yes", job->yes, "start a render estimated at over an hour");
    cmd->add_flag("--list-presets", job->list, "print the preset names");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] { exitCode = runRender(*job); });
}

} // namespace bmfr::app
