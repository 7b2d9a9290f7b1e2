#include "commands.h"
#include "eval/comparison.h"
#include "io/output_folder.h"
#include "peers/oidn_library.h"
#include "progress.h"
#include "render/sequence_renderer.h"
#include "usage.h"
#include <filesystem>
#include <fmt/core.h>

namespace bmfr::app {

void addDemoCommand(CLI::App& app, int& exitCode) {
    struct DemoJob {
        std::string output = "bmfr-demo", scene = "cornell-moving", scenesDir = "../shared/scenes";
        // Small enough that install, build and demo take under five minutes on 2 cores.
        int width = 256, height = 192, frames = 24, referenceSpp = 128;
        bool quiet = false;
    };
    auto job = std::make_shared<DemoJob>();
    CLI::App* cmd = app.add_subcommand(
        "demo",
        "path trace a short built-in sequence, denoise it, score it, write images and the report");
    cmd->add_option("-o,--output", job->output, "output directory")->default_val("bmfr-demo");
    cmd->add_option("-s,--scene", job->scene, "preset or scene description")
        ->default_val("cornell-moving");
    cmd->add_option("--scenes", job->scenesDir, "folder holding sponza/ (for the presets)")
        ->default_val("../shared/scenes");
    cmd->add_option("--width", job->width, "pixels")
        ->check(integerIn(1, render::kMaxSceneSide))
        ->default_val(256);
    cmd->add_option("--height", job->height, "pixels")
        ->check(integerIn(1, render::kMaxSceneSide))
        ->default_val(192);
    cmd->add_option("--frames", job->frames, "frame count")
        ->check(integerIn(1, render::kMaxSceneFrames))
        ->default_val(24);
    cmd->add_option("--reference-spp", job->referenceSpp, "reference samples per pixel")
        ->check(integerIn(0, 1 << 20))
        ->default_val(128);
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->callback([job, &exitCode] {
        namespace fs = std::filesystem;
        render::SceneDescription d = render::loadSceneDescription(job->scene, job->scenesDir);
        d.width = job->width, d.height = job->height, d.frames = job->frames;
        d.referenceSpp = job->referenceSpp;
        const OutputFolder folder(job->output, invocation());
        const std::string input = (fs::path(job->output) / "input").string();
        if (!job->quiet)
            fmt::print(
                "bmfr demo: rendering {} ({}x{}, {} frames, 1 spp + {} spp reference) into {}\n",
                d.name, d.width, d.height, d.frames, d.referenceSpp, input);
        Progress progress("render", d.frames, job->quiet);
        render::SequenceRenderReport r = render::renderSequence(
            d, {input, "manifest", job->quiet}, nullptr,
            [&](int done, int) { progress.step(done); },
            [&](const std::string& w) { fmt::print(stderr, "bmfr: warning: {}\n", w); });
        progress.finish();
        if (!job->quiet && r.rendered)
            fmt::print(
                "rendered {} frames: {:.3f} s per 1-spp frame, {:.2f} s per reference frame\n\n",
                r.rendered, r.inputSeconds / r.rendered, r.referenceSeconds / r.rendered);
        // BMFR (the default, quality preset) and two ablations, as the paper compares them, SVGF
        // and WALR, BMFR and SVGF as their papers have them (the faithful preset), Mara 2017,
        // OIDN where it is installed, then the report. Where objects move, also BMFR by the camera
        // path alone (the paper's reprojection).
        struct Variant {
            const char* name;
            const char* folder;
            std::vector<std::string> disabled;
            const char* filter;
            bool motion = true;
            const char* preset = "quality";
        };
        std::vector<Variant> variants = {
            {"bmfr", "denoised", {}, "bmfr"},
            {"accumulation only", "accumulation_only", {"fitting"}, "bmfr"},
            {"bmfr without TAA", "bmfr_no_taa", {"taa"}, "bmfr"},
            {"svgf", "svgf", {}, "svgf"},
            {"walr", "walr", {}, "walr"},
            {"bmfr faithful", "bmfr_faithful", {}, "bmfr", true, "faithful"},
            {"svgf faithful", "svgf_faithful", {}, "svgf", true, "faithful"}};
        if (!d.animations.empty() || d.gltfAnimationFps > 0)
            variants.push_back({"bmfr camera path", "bmfr_camera_path", {}, "bmfr", false});
        ComparisonOptions eval;
        eval.reference = input;
        eval.output = (fs::path(job->output) / "report").string();
        eval.methods.push_back({"noisy", ""});
        for (const Variant& v : variants) {
            DenoiseJob dj;
            dj.input = input;
            dj.output = (fs::path(job->output) / v.folder).string();
            const bool main = v.disabled.empty() && std::string(v.filter) == "bmfr" &&
                              std::string(v.preset) == "quality";
            dj.quiet = job->quiet || !main; // the full summary for BMFR itself
            dj.debug = main;
            dj.filter = v.filter;
            dj.options.disabled = v.disabled;
            dj.options.preset = v.preset;
            dj.motion = v.motion;
            dj.overwrite = true; // the demo's own folder: a second demo replaces the first's
            runDenoise(dj);
            eval.methods.push_back({v.name, dj.output});
        }
        // Mara et al. 2017 filters its own factored paths: the same frames rendered that way
        // (other noise, no reference of their own), scored against the same reference.
        {
            render::SceneDescription m = d;
            m.referenceSpp = 0;
            m.factoredDirectSpp = 16;
            DenoiseJob dj;
            dj.input = (fs::path(job->output) / "mara_input").string();
            render::renderSequence(
                m, {dj.input, "manifest", true}, nullptr, [](int, int) {},
                [](const std::string& w) { fmt::print(stderr, "bmfr: warning: {}\n", w); });
            dj.output = (fs::path(job->output) / "mara2017").string();
            dj.quiet = true;
            dj.filter = "mara2017";
            dj.overwrite = true;
            runDenoise(dj);
            eval.methods.push_back({"mara2017", dj.output});
        }
        // What users run today, beside them, where it is installed.
        if (const std::string why = oidn::whyUnavailable(); why.empty()) {
            DenoiseJob dj = oidnJob(input, (fs::path(job->output) / "oidn").string());
            dj.quiet = true;
            dj.overwrite = true;
            runDenoise(dj);
            eval.methods.push_back({"oidn", dj.output});
        } else if (!job->quiet) {
            fmt::print("The comparison runs without Intel Open Image Denoise: {}\n", why);
        }
        exitCode = runEval(eval, job->quiet);
    });
}

} // namespace bmfr::app
