#include "usage.h"
#include <bmfr/filter.h>
#include <cctype>
#include <cstdio>
#include <fmt/format.h>

namespace bmfr::app {

std::string commandList(const CLI::App& app) {
    std::string s = "commands:\n";
    for (const CLI::App* sub : app.get_subcommands({}))
        s += fmt::format("  {:<10} {}\n", sub->get_name(), sub->get_description());
    return s +
           "run 'bmfr COMMAND --help' for a command's options, 'bmfr --version' for the build\n";
}

namespace {

std::string usageLine(const CLI::App& cmd) {
    std::string s = "usage: bmfr " + cmd.get_name();
    auto upper = [](std::string t) {
        for (char& c : t) c = char(std::toupper(static_cast<unsigned char>(c)));
        return t;
    };
    for (const CLI::Option* o : cmd.get_options()) {
        if (o->get_positional()) {
            const std::string n = upper(o->get_name());
            s += o->get_required() ? " " + n : " [" + n + "]";
        } else if (o->get_required()) {
            const std::string flags = o->get_name(false, true);
            const std::string longName = o->get_lnames().empty() ? "VALUE" : o->get_lnames()[0];
            s += " " + flags.substr(0, flags.find(',')) + " " + upper(longName);
        }
    }
    return s + " [options]";
}

} // namespace

int reportUsageError(const CLI::App& app, const CLI::ParseError& error) {
    const CLI::App* active = nullptr;
    for (const CLI::App* sub : app.get_subcommands({}))
        if (sub->parsed()) active = sub;
    std::fprintf(stderr, "bmfr: %s\n", error.what());
    if (active)
        std::fprintf(stderr, "%s\nrun 'bmfr %s --help' for the options\n",
                     usageLine(*active).c_str(), active->get_name().c_str());
    else
        std::fprintf(stderr, "usage: bmfr COMMAND [options]\n%s", commandList(app).c_str());
    return 2;
}

std::string describeForCli(const SettingError& error) {
    for (const std::string& filter : filterNames())
        for (const SettingDoc& d : filterSettings(filter))
            if (d.key == error.key())
                return fmt::format("--{} {} {}", d.flag, error.value(), error.problem());
    return error.what();
}

} // namespace bmfr::app
