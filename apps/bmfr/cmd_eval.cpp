#include "commands.h"
#include "eval/comparison.h"
#include "eval/score_tables.h"
#include "io/output_folder.h"
#include "io/range_parsers.h"
#include "progress.h"
#include "usage.h"
#include <bmfr/error.h>
#include <filesystem>
#include <fmt/core.h>
#include <memory>

namespace bmfr::app {

int runEval(const ComparisonOptions& options, bool quiet, bool json,
            const std::optional<DenoiseJob>& oidnFirst) {
    ComparisonOptions o = options;
    if (o.commandLine.empty()) o.commandLine = invocation();
    if (o.programVersion.empty()) o.programVersion = versionText();
    const OutputFolder folder(o.output, invocation());
    std::unique_ptr<Progress> bar; // the frame count is known once the reference is open
    ComparisonResult r;
    std::error_code ec;
    // What a failed eval may remove: the peer's folder, when this run made it.
    const bool peerFolderWasThere = oidnFirst && std::filesystem::exists(oidnFirst->output, ec);
    try {
        if (oidnFirst) {
            if (!quiet && !json)
                fmt::print("eval --oidn: denoising {} with Intel Open Image Denoise into {}\n",
                           oidnFirst->input, oidnFirst->output);
            runDenoise(*oidnFirst);
            o.methods.push_back({"oidn", oidnFirst->output});
        }
        r = runComparison(o, [&](int done, int total) {
            if (!bar) bar = std::make_unique<Progress>("eval", total, quiet);
            bar->step(done);
        });
    } catch (const std::exception&) {
        if (oidnFirst && !peerFolderWasThere) std::filesystem::remove_all(oidnFirst->output, ec);
        throw;
    }
    if (bar) bar->finish();
    if (json) {
        fmt::print("{}", r.scoresJson);
    } else if (!quiet) {
        fmt::print("\nScores, mean over frames {}:{} (tone-mapped; relMSE linear):\n\n{}\n",
                   r.first, r.last, markdownTable(r));
        for (const std::string& v : r.videos) fmt::print("video: {}\n", v);
        fmt::print("report: {}\n", r.reportPath);
    }
    return 0;
}

void addEvalCommand(CLI::App& app, int& exitCode) {
    struct Job {
        ComparisonOptions options;
        std::vector<std::string> methods, crops, channels;
        bool quiet = false, noFlip = false, json = false, oidn = false;
    };
    auto job = std::make_shared<Job>();
    CLI::App* cmd =
        app.add_subcommand("eval", "score result sequences against a reference: tables, plots, "
                                   "insets, heat maps, videos and an HTML report with a viewer");
    cmd->add_option("-r,--reference", job->options.reference,
                    "sequence folder holding the reference frames")
        ->required();
    cmd->add_option(
           "-m,--method", job->methods,
           "NAME=PATH: a `bmfr denoise` output or a sequence (its noisy colour); NAME alone = the "
           "reference sequence's noisy colour")
        ->required();
    cmd->add_option("-o,--output", job->options.output, "output folder")->required();
    cmd->add_option("--frames", job->options.frames, "frame range A:B (A..B-1)");
    cmd->add_option("--crop", job->crops,
                    "x,y,w,h inset (repeatable); default: where the methods differ most");
    cmd->add_option("--crops", job->options.autoCrops,
                    "automatic insets when no --crop, from distinct parts of the frame")
        ->default_val(3);
    cmd->add_option("--crop-size", job->options.cropSize, "automatic inset size, pixels")
        ->default_val(48);
    cmd->add_option("--zoom", job->options.zoom, "inset enlargement")->default_val(4);
    cmd->add_option("--show-frame", job->options.showFrame,
                    "frame for pictures and heat maps (default: last)");
    cmd->add_flag("--no-flip", job->noFlip, "skip FLIP (the slowest metric)");
    cmd->add_option("--log-plots", job->options.logPlots,
                    "auto: a log y axis where a metric's values span more than 10x; on; off")
        ->check(oneOf({"auto", "on", "off"}))
        ->default_val("auto");
    cmd->add_flag("--video", job->options.video,
                  "also write methods.mp4 (side by side) and flicker.mp4 (frame-to-frame "
                  "change) with ffmpeg (H.264)");
    cmd->add_option("--video-fps", job->options.videoFps,
                    "frames per second of the videos and of the report viewer's playback, 1-120")
        ->default_val(24);
    cmd->add_option("--viewer-width", job->options.viewerWidth,
                    "pixels: wider frames are embedded downscaled in the viewer (full-size PNGs "
                    "beside the report), 64-4096")
        ->default_val(640);
    cmd->add_option("--channel", job->channels,
                    "BUFFER=LAYER: the reference sequence's layer for a buffer in multilayer "
                    "EXRs, as reference=ViewLayer.Combined; repeatable");
    cmd->add_flag("--oidn", job->oidn,
                  "also denoise the reference sequence's noisy input with Intel Open Image Denoise "
                  "(bmfr peer oidn, its defaults) into OUTPUT/oidn and score it as `oidn`");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    cmd->add_flag("--json", job->json,
                  "print the scores as JSON on stdout (as table.json) instead of the table");
    cmd->callback([job, &exitCode] {
        ComparisonOptions o = job->options;
        for (const std::string& m : job->methods) {
            size_t eq = m.find('=');
            o.methods.push_back(eq == std::string::npos
                                    ? MethodSource{m, ""}
                                    : MethodSource{m.substr(0, eq), m.substr(eq + 1)});
        }
        for (const std::string& c : job->crops)
            o.crops.push_back(usageChecked([&] { return parseCrop(c); }));
        o.referenceLayers = usageChecked([&] { return parseLayerMap(job->channels); });
        // A range that does not parse is the command line's error; one the input lacks is the
        // input's.
        usageChecked([&] { checkFrameRangeSyntax(o.frames); });
        if (o.zoom < 1 || o.zoom > 16) throw UsageError("--zoom must be in [1, 16]");
        if (o.autoCrops < 0 || o.autoCrops > 16) throw UsageError("--crops must be in [0, 16]");
        if (o.cropSize < 4 || o.cropSize > 1024)
            throw UsageError("--crop-size must be in [4, 1024]");
        if (o.videoFps < 1 || o.videoFps > 120) throw UsageError("--video-fps must be in [1, 120]");
        if (o.viewerWidth < 64 || o.viewerWidth > 4096)
            throw UsageError("--viewer-width must be in [64, 4096]");
        o.flip = !job->noFlip;
        std::optional<DenoiseJob> oidnFirst;
        if (job->oidn) {
            DenoiseJob dj =
                oidnJob(o.reference, (std::filesystem::path(o.output) / "oidn").string());
            dj.frames = o.frames;
            dj.channels = job->channels;
            dj.quiet = true;
            dj.png = dj.flip = false;
            dj.overwrite = true; // eval's own folder: a second eval replaces the first's
            oidnFirst = dj;
        }
        for (size_t i = 0; i < o.methods.size(); ++i)
            for (size_t k = 0; k < i; ++k)
                if (o.methods[i].name == o.methods[k].name)
                    throw UsageError("-m: two methods are named '" + o.methods[i].name +
                                     "'; give each its own name");
        if (oidnFirst)
            for (const MethodSource& m : o.methods)
                if (m.name == "oidn")
                    throw UsageError("--oidn scores its run as 'oidn', and a -m method has that "
                                     "name; rename it");
        exitCode = runEval(o, job->quiet, job->json, oidnFirst);
    });
}

} // namespace bmfr::app
