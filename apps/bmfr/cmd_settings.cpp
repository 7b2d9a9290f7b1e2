// `bmfr settings`: every filter's settings table, as text or as docs/settings.md's Markdown.
#include "commands.h"
#include "usage.h"
#include <fmt/core.h>

namespace bmfr::app {

namespace {

/// A table cell: '|' would end it.
std::string escape(const std::string& s) {
    std::string r;
    for (char c : s) r += c == '|' ? std::string("\\|") : std::string(1, c);
    return r;
}

std::string markdown() {
    std::string out = "| filter | key | flag | unit | range | default | faithful | what it does |\n"
                      "|---|---|---|---|---|---|---|---|\n";
    bool sharedDone = false;
    for (const std::string& f : filterNames()) {
        for (const SettingDoc& d : filterSettings(f)) {
            if (d.shared && sharedDone) continue; // the same rows in every table
            out += fmt::format("| {} | `{}` | `--{}` | {} | {} | {} | {} | {} |\n",
                               d.shared ? "all" : f, d.key, d.flag, d.unit, d.range,
                               escape(d.defaultValue), escape(d.faithful), escape(d.help));
        }
        sharedDone = true;
    }
    return out;
}

} // namespace

void addSettingsCommand(CLI::App& app, int& exitCode) {
    struct Job {
        std::string filter, preset;
        bool markdown = false, quiet = false;
    };
    auto job = std::make_shared<Job>();
    CLI::App* cmd = app.add_subcommand(
        "settings", "every setting of a filter: key, flag, unit, range, default and help");
    cmd->add_option("filter", job->filter, "one filter (default: all)")
        ->check(oneOf(filterNames()));
    cmd->add_flag("--markdown", job->markdown, "docs/settings.md's table");
    cmd->add_option(
           "--preset", job->preset,
           "print only what this preset sets (quality: nothing, it is the default; faithful: "
           "the papers' values), as key=value")
        ->check(oneOf(presetNames()));
    cmd->add_flag("-q,--quiet", job->quiet,
                  "accepted on every command; the table is this command's result");
    cmd->callback([job, &exitCode] {
        if (!job->preset.empty()) {
            std::vector<std::string> names = filterNames();
            if (!job->filter.empty()) names = {job->filter};
            for (const std::string& f : names) {
                fmt::print("{}:", f);
                for (const auto& [k, v] : presetSettings(f, job->preset))
                    fmt::print(" {}={}", k, v);
                fmt::print("\n");
            }
        } else if (job->markdown) {
            fmt::print("{}", markdown());
        } else {
            std::vector<std::string> names = filterNames();
            if (!job->filter.empty()) names = {job->filter};
            for (const std::string& f : names) {
                fmt::print("{}:\n", f);
                for (const SettingDoc& d : filterSettings(f))
                    fmt::print("  {:<24} --{:<30} {:<14} {:<18} default {:<10} {}\n", d.key, d.flag,
                               d.unit, d.range, d.defaultValue, d.help);
            }
        }
        exitCode = 0;
    });
}

} // namespace bmfr::app
