// Subcommands of the bmfr tool and the denoise job they share.
#pragma once
#include "eval/comparison.h"
#include "filter_options.h"
#include "peers/oidn_filter.h"
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace bmfr::app {

struct DenoiseJob {
    std::string input, output;
    std::string frames; ///< "A:B" (A..B-1), "A:" or ":B"; empty = all
    bool quiet = false, debug = false, png = true, flip = true;
    bool motion = true;     ///< reproject through the sequence's motion vectors when it has them
    bool overwrite = false; ///< replace an earlier run's outputs in `output` instead of refusing
    std::string filter = "bmfr"; ///< a name from filterNames()
    float sampleFraction = 1.0f; ///< < 1 simulates fewer than 1 spp with a per-frame pixel mask
    std::vector<std::string> channels; ///< BUFFER=LAYER for multilayer EXR inputs
    FilterOptions options;
    /// A peer method (`bmfr peer oidn`) in place of a filter: `filter` and `options` unused.
    std::optional<oidn::PeerSettings> oidn;
};

/// The job `bmfr peer oidn INPUT -o OUTPUT` runs with its defaults (the demo and eval --oidn
/// run it into their own folders, replacing an earlier run's outputs there).
DenoiseJob oidnJob(const std::string& input, const std::string& output);

/// Denoises a sequence into job.output; prints a timing summary (and scores when the input has
/// references). Returns the process exit code.
int runDenoise(const DenoiseJob& job);

/// The command line this process was started with, shell-quoted where needed.
const std::string& invocation();
/// "bmfr VERSION (commit ...; backends: ...)", as --version prints.
std::string versionText();

/// Runs `bmfr eval`; prints the table and the report path unless quiet, or with `json` the
/// scores as JSON on stdout. With `oidnFirst`, first runs that peer job into the eval's own
/// folder (under its lock) and scores it as `oidn`; a failed eval removes what it wrote.
int runEval(const ComparisonOptions& options, bool quiet, bool json = false,
            const std::optional<DenoiseJob>& oidnFirst = std::nullopt);

void addDenoiseCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);
void addDemoCommand(CLI::App& app, int& exitCode);
void addSynthCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addTonemapCommand(CLI::App& app, int& exitCode);
void addEvalCommand(CLI::App& app, int& exitCode);
void addAblateCommand(CLI::App& app, int& exitCode);
void addSettingsCommand(CLI::App& app, int& exitCode);
void addSoakCommand(CLI::App& app, int& exitCode);
void addPeerCommand(CLI::App& app, int& exitCode);
void addBatchCommand(CLI::App& app, int& exitCode);

} // namespace bmfr::app
