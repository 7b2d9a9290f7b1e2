#include "commands.h"
#include "help_format.h"
#include "io/sequence.h"
#include "usage.h"
#include <fmt/format.h>

namespace bmfr::app {

DenoiseJob oidnJob(const std::string& input, const std::string& output) {
    DenoiseJob job;
    job.input = input;
    job.output = output;
    job.filter = "oidn";
    job.oidn = oidn::PeerSettings();
    return job;
}

void addPeerCommand(CLI::App& app, int& exitCode) {
    CLI::App* peer = app.add_subcommand(
        "peer", "run a method bmfr is compared with on a sequence, writing what `bmfr denoise` "
                "writes, so that `bmfr eval` scores it beside the filters");
    peer->require_subcommand(1);
    auto job = std::make_shared<DenoiseJob>(oidnJob("", ""));
    CLI::App* cmd = peer->add_subcommand(
        "oidn", "Intel Open Image Denoise's RT filter on each frame alone (colour, albedo, "
                "normal): denoised_NNNN.exr (linear) and .png, report.json, scores.csv");
    cmd->add_option("input", job->input, "input directory")->required();
    cmd->add_option("-o,--output", job->output, "output directory")->required();
    cmd->add_option("--frames", job->frames, "frame range A:B (A..B-1), A: or :B");
    cmd->add_option("--quality", job->oidn->quality,
                    "OIDN's quality: fast, balanced or high (OIDN's default)")
        ->check(oneOf(oidn::qualityNames()))
        ->default_val("high");
    cmd->add_option("--prefilter", job->oidn->prefilter,
                    "albedo and normal, as Blender names it: none (passed as noise free), fast "
                    "(passed as possibly noisy) or accurate (denoised first; Blender's default)")
        ->check(oneOf(oidn::prefilterNames()))
        ->default_val("accurate");
    cmd->add_option("--threads", job->oidn->threads, "OIDN's worker threads; 0 = every core")
        ->check(integerIn(0, 1024))
        ->default_val(0);
    cmd->add_option("--oidn-library", job->oidn->library,
                    "libOpenImageDenoise.so.2 to load (default: $BMFR_OIDN_LIBRARY, then the one "
                    "scripts/install-oidn.sh installed, then the system's)");
    cmd->add_option("--channel", job->channels,
                    "BUFFER=LAYER: read a buffer from this layer of multilayer EXRs, as "
                    "albedo=ViewLayer.DiffCol; repeatable");
    cmd->add_flag("--overwrite", job->overwrite,
                  "replace the outputs of an earlier run in OUTPUT instead of refusing them");
    cmd->add_flag("!--no-png", job->png, "skip the tone-mapped PNGs");
    cmd->add_flag("!--no-flip", job->flip, "skip FLIP when scoring (the slowest metric)");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    setHelpIntro(cmd, R"(examples:
  bash scripts/install-oidn.sh        # once: OIDN 2.5.1 from PyPI (pyoidn) into .venv/
  bmfr peer oidn bmfr-demo/input -o oidn
  bmfr eval -r bmfr-demo/input -m noisy -m bmfr=bmfr-demo/denoised -m oidn=oidn -o cmp

OIDN denoises every frame alone: it keeps no history, so it neither lags nor ghosts, and its
frames flicker as their noise does. Times are OIDN's own per frame (report.json, median_ms).)");
    cmd->callback([job, &exitCode] { exitCode = runDenoise(*job); });
}

} // namespace bmfr::app
