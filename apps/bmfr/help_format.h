// How `bmfr COMMAND --help` reads: usage first, then what the command does, examples and the
// input it wants, then the options in groups (the command's own, then settings every filter
// has, then those of the filter chosen with --filter, bmfr by default). Defaults are said once,
// in the option's line.
#pragma once
#include <CLI/CLI.hpp>
#include <string>

namespace bmfr::app {

class HelpFormatter : public CLI::Formatter {
  public:
    HelpFormatter();
    std::string make_help(const CLI::App* app, std::string name,
                          CLI::AppFormatMode mode) const override;
    std::string make_option(const CLI::Option* opt, bool positional) const override;
    std::string make_description(const CLI::App* app) const override;
    std::string make_usage(const CLI::App* app, std::string name) const override;
    std::string make_option_name(const CLI::Option* opt, bool positional) const override;
    std::string make_option_opts(const CLI::Option* opt) const override;
    std::string make_option_desc(const CLI::Option* opt) const override;

  private:
    /// CLI11's make_groups (not virtual), showing one filter's settings.
    std::string groups(const CLI::App* app) const;
};

/// Text that `cmd --help` prints after its usage line and description: examples, the input.
void setHelpIntro(const CLI::App* cmd, std::string text);

} // namespace bmfr::app
