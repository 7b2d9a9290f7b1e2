// Subcommands of the bmfr tool and the denoise job they share.
#pragma once
#include "eval/comparison.h"
#include <CLI/CLI.hpp>
#include <bmfr/settings.h>
#include <bmfr/svgf.h>
#include <optional>
#include <string>

namespace bmfr::app {

/// Settings given on the command line; unset values fall back to the sequence, then defaults.
struct SettingsOptions {
    Settings settings;
    std::optional<float> positionLimitSquared, normalLimitSquared;
    std::string features;
    std::vector<std::string> disabled;
    void addTo(CLI::App& cmd);
    /// Resolves against what the sequence recommends. Throws bmfr::Error.
    Settings resolve(std::optional<float> seqPositionLimit, std::optional<float> seqNormalLimit,
                     bool colorIsDemodulated) const;
};

struct DenoiseJob {
    std::string input, output;
    std::string frames; ///< "A:B" (A..B-1), "A:" or ":B"; empty = all
    bool quiet = false, debug = false, png = true, flip = true;
    std::string filter = "bmfr"; ///< "bmfr" or "svgf"
    SvgfSettings svgf;
    float sampleFraction = 1.0f; ///< < 1 simulates fewer than 1 spp with a per-frame pixel mask
    SettingsOptions options;
};

/// Denoises a sequence into job.output; prints a timing summary (and scores when the input has
/// references). Returns the process exit code.
int runDenoise(const DenoiseJob& job);

/// Runs `bmfr eval`; prints the table and the report path unless quiet.
int runEval(const ComparisonOptions& options, bool quiet);

void addDenoiseCommand(CLI::App& app, int& exitCode);
void addBenchCommand(CLI::App& app, int& exitCode);
void addDemoCommand(CLI::App& app, int& exitCode);
void addSynthCommand(CLI::App& app, int& exitCode);
void addRenderCommand(CLI::App& app, int& exitCode);
void addTonemapCommand(CLI::App& app, int& exitCode);
void addEvalCommand(CLI::App& app, int& exitCode);
void addAblateCommand(CLI::App& app, int& exitCode);

} // namespace bmfr::app
