// How the CLI reports usage errors: `bmfr:` prefix, the command's usage line, exit code 2, and
// messages in the CLI's own words (never the parser's).
#pragma once
#include <CLI/CLI.hpp>
#include <bmfr/error.h>
#include <string>
#include <vector>

namespace bmfr::app {

/// A command line that asks for something that does not exist or cannot be: exit 2.
class UsageError : public Error {
  public:
    using Error::Error;
};

/// f(), with a bmfr::Error it throws (a flag's value that does not parse) as a UsageError.
template <class F> auto usageChecked(F&& f) -> decltype(f()) {
    try {
        return f();
    } catch (const UsageError&) {
        throw;
    } catch (const Error& e) {
        throw UsageError(e.what());
    }
}

/// "usage: bmfr denoise INPUT -o OUTPUT [options]".
std::string usageLine(const CLI::App& cmd);
/// The command's words after `bmfr`: "denoise", "peer oidn".
std::string commandPath(const CLI::App& cmd);

/// "commands:" and one line per subcommand with its description.
std::string commandList(const CLI::App& app);

/// Prints `bmfr: MESSAGE`, the usage line of the command being parsed (or the command list when
/// no command was recognised) and a pointer to --help. Returns 2.
int reportUsageError(const CLI::App& app, const std::string& message);
/// The parser's error in the CLI's words ("unknown option '--blok-size' (did you mean
/// '--block-size'?)"), reported as above.
int reportUsageError(const CLI::App& app, const CLI::ParseError& error);

/// A settings error of `filter` in the CLI's words: `--block-size 7 is outside [8, 64]` (keys
/// such as `seed` are settings of several filters, under other flags).
std::string describeForCli(const SettingError& error, const std::string& filter);

/// "TEXT" for "text": the CLI's placeholders for values.
std::string upperCase(std::string text);

/// The backends a command line may name, as the library names them (`bmfr --version` says
/// which this build has).
std::vector<std::string> backendNames();

/// A validator for an option that takes one of `names`: "'fast' is not one of faithful,
/// quality", with "did you mean" for a near miss.
CLI::Validator oneOf(std::vector<std::string> names);
/// A validator for an integer option in [lo, hi]: "5000 is outside [1, 4096]".
CLI::Validator integerIn(long long lo, long long hi);

} // namespace bmfr::app
