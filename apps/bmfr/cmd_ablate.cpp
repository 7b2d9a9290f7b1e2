#include "commands.h"
#include "eval/ablation.h"
#include "filters/bmfr/bmfr_settings_table.h"
#include "io/output_folder.h"
#include "io/sequence.h"
#include <fmt/core.h>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace bmfr::app {

void addAblateCommand(CLI::App& app, int& exitCode) {
    struct Job {
        std::string input, output, frames;
        bool quiet = false;
        FilterOptions options;
    };
    auto job = std::make_shared<Job>();
    CLI::App* cmd = app.add_subcommand(
        "ablate", "BMFR ablations: each stage off in turn, and the paper's greedy "
                  "feature-set study, scored against the references");
    cmd->add_option("input", job->input, "sequence folder with references")->required();
    cmd->add_option("-o,--output", job->output, "output folder")->required();
    cmd->add_option("--frames", job->frames, "frame range A:B (A..B-1)");
    cmd->add_flag("-q,--quiet", job->quiet, "no progress or summary");
    job->options.addTo(*cmd, {"bmfr"});
    cmd->callback([job, &exitCode] {
        usageChecked([&] { checkFrameRangeSyntax(job->frames); });
        auto reader = SequenceReader::open(job->input);
        const SequenceInfo& info = reader->info();
        const SequenceDefaults own{info.positionLimitSquared, info.normalLimitSquared,
                                   info.colorIsDemodulated};
        BmfrSettings base;
        try {
            applySettings(bmfrSettingsTable(), base, job->options.resolve("bmfr", own), "bmfr");
            validate(base);
        } catch (const SettingError& e) {
            job->options.rethrow("bmfr", e, own);
        }
        const OutputFolder folder(job->output, invocation());
        int n = 0;
        const bool terminal = isatty(2);
        runAblation(job->input, job->output, job->frames, base, [&](const std::string& name) {
            if (job->quiet) return;
            // A carriage return redraws a terminal's line; a log gets one line per configuration.
            if (terminal)
                fmt::print(stderr, "\rablate: configuration {} ({})          ", ++n, name);
            else
                fmt::print(stderr, "ablate: configuration {} ({})\n", ++n, name);
        });
        if (!job->quiet) {
            std::ifstream md(std::filesystem::path(job->output) / "ablation.md");
            std::stringstream ss;
            ss << md.rdbuf();
            if (terminal) fmt::print(stderr, "\n");
            fmt::print("{}\nwrote {}/ablation.md, .csv, .json and plot_greedy_*.png\n", ss.str(),
                       job->output);
        }
        exitCode = 0;
    });
}

} // namespace bmfr::app
