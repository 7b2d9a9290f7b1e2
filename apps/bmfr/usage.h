// How the CLI reports usage errors: `bmfr:` prefix, the command's usage line, exit code 2.
#pragma once
#include <CLI/CLI.hpp>
#include <bmfr/error.h>
#include <string>

namespace bmfr::app {

/// "commands:" and one line per subcommand with its description.
std::string commandList(const CLI::App& app);

/// Prints `bmfr: MESSAGE`, the usage line of the command being parsed (or the command list when
/// no command was recognised) and a pointer to --help. Returns 2.
int reportUsageError(const CLI::App& app, const CLI::ParseError& error);

/// A settings error in the CLI's words: `--block-size 7 is outside [8, 64]`.
std::string describeForCli(const SettingError& error);

} // namespace bmfr::app
