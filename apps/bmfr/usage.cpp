#include "usage.h"
#include "core/closest_name.h"
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

std::string commandPath(const CLI::App& cmd) {
    std::string s = cmd.get_name();
    for (const CLI::App* p = cmd.get_parent(); p && p->get_parent(); p = p->get_parent())
        s = p->get_name() + " " + s;
    return s;
}

std::string usageLine(const CLI::App& cmd) {
    std::string s = "usage: bmfr " + commandPath(cmd);
    if (cmd.get_require_subcommand_min() > 0) s += " COMMAND";
    for (const CLI::Option* o : cmd.get_options()) {
        if (o->get_positional()) {
            const std::string n = upperCase(o->get_name());
            s += o->get_required() ? " " + n : " [" + n + "]";
        } else if (o->get_required()) {
            const std::string flags = o->get_name(false, true);
            const std::string longName = o->get_lnames().empty() ? "VALUE" : o->get_lnames()[0];
            s += " " + flags.substr(0, flags.find(',')) + " " + upperCase(longName);
        }
    }
    return s + " [options]";
}

namespace {

/// The innermost command given ("oidn" of `bmfr peer oidn`), or null.
const CLI::App* activeCommand(const CLI::App& app) {
    const CLI::App* active = nullptr;
    for (const CLI::App* sub : app.get_subcommands({}))
        if (sub->parsed()) active = sub;
    if (active)
        if (const CLI::App* inner = activeCommand(*active)) return inner;
    return active;
}

/// The long option names of `cmd`, as "name" without the dashes.
std::vector<std::string> longNames(const CLI::App& cmd) {
    std::vector<std::string> names;
    for (const CLI::Option* o : cmd.get_options())
        for (const std::string& n : o->get_lnames()) names.push_back(n);
    return names;
}

/// What the parser could not place: the first unknown option, or else the first extra value.
std::string describeExtras(const CLI::App& app, const CLI::App& cmd) {
    // After "--", what is left belongs to the whole command line, not to the command.
    std::vector<std::string> extras = cmd.remaining();
    if (extras.empty()) extras = app.remaining(true);
    for (const std::string& arg : extras)
        if (arg.size() > 1 && arg[0] == '-') {
            const std::string name = arg.substr(0, arg.find('='));
            std::string bare = name;
            bare.erase(0, bare.find_first_not_of('-'));
            return fmt::format("unknown option '{}'{}", name,
                               didYouMean(bare, longNames(cmd), "--"));
        }
    if (!extras.empty())
        return fmt::format("unexpected argument '{}' (an option's value, or one input too many?)",
                           extras.front());
    return "unexpected arguments";
}

/// CLI11's "--width: 1 required INT missing", "Could not convert: --width = abc" and the like.
std::string translate(const CLI::App& app, const CLI::ParseError& error) {
    const std::string text = error.what();
    const CLI::App* active = activeCommand(app);
    if (dynamic_cast<const CLI::ExtrasError*>(&error))
        return describeExtras(app, active ? *active : app);
    if (dynamic_cast<const CLI::RequiredError*>(&error)) {
        // A command of commands given none (`bmfr peer`): name them.
        if (active && active->get_require_subcommand_min() > 0 &&
            text.find("subcommand") != std::string::npos) {
            std::vector<std::string> names;
            for (const CLI::App* sub : active->get_subcommands({}))
                names.push_back(sub->get_name());
            return fmt::format("bmfr {} needs a command: {}", commandPath(*active),
                               fmt::join(names, ", "));
        }
        // "input is required" for a positional, "--output is required" for an option.
        const std::string name = text.substr(0, text.find(' '));
        return (name.rfind("-", 0) == 0 ? name : upperCase(name)) + " is required";
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
        const std::string name = text.substr(0, text.find(':'));
        if (text.find(": At Most ") != std::string::npos) return name + " is given more than once";
        if (text.find("disallowed flag override") != std::string::npos)
            return text.substr(0, text.find(' ')) + " takes no value";
        return name + " needs a value";
    }
    // "--width abc" expects a number, "--quiet=maybe" true or false.
    auto badValue = [&](const std::string& name, const std::string& value) {
        const CLI::Option* o = active ? active->get_option_no_throw(name) : nullptr;
        const bool flag = o && o->get_expected_max() == 0;
        return fmt::format("{} {}: not a valid value ({} expected)", name, value,
                           flag ? "true or false is" : "a number is");
    };
    if (dynamic_cast<const CLI::ConversionError*>(&error)) {
        const std::string convert = "Could not convert: ";
        if (text.rfind(convert, 0) == 0) { // "Could not convert: --width = abc"
            const std::string rest = text.substr(convert.size());
            const size_t eq = rest.find(" = ");
            if (eq != std::string::npos) return badValue(rest.substr(0, eq), rest.substr(eq + 3));
        }
        const std::string allowed = "The value ";
        if (text.rfind(allowed, 0) == 0) { // "The value abc is not an allowed value for --w"
            const size_t is = text.find(" is not an allowed value for ");
            if (is != std::string::npos)
                return badValue(text.substr(is + 29), text.substr(10, is - 10));
        }
        const size_t colon = text.find(": Should be true/false");
        if (colon != std::string::npos) return text.substr(0, colon) + ": expected true or false";
    }
    return text;
}

} // namespace

int reportUsageError(const CLI::App& app, const std::string& message) {
    const CLI::App* active = activeCommand(app);
    std::fprintf(stderr, "bmfr: %s\n", message.c_str());
    if (active)
        std::fprintf(stderr, "%s\nrun 'bmfr %s --help' for the options\n",
                     usageLine(*active).c_str(), commandPath(*active).c_str());
    else
        std::fprintf(stderr, "usage: bmfr COMMAND [options]\n%s", commandList(app).c_str());
    return 2;
}

int reportUsageError(const CLI::App& app, const CLI::ParseError& error) {
    return reportUsageError(app, translate(app, error));
}

std::string upperCase(std::string text) {
    for (char& c : text) c = char(std::toupper(static_cast<unsigned char>(c)));
    return text;
}

std::string describeForCli(const SettingError& error, const std::string& filter) {
    // "--block-size 7 is outside [8, 64]", but "--backend gpu: unknown backend 'gpu'".
    const std::string& p = error.problem();
    const bool predicate = p.rfind("is ", 0) == 0 || p.rfind("must ", 0) == 0;
    for (const SettingDoc& d : filterSettings(filter))
        if (d.key == error.key())
            return fmt::format("--{} {}{}{}", d.flag, error.value(), predicate ? " " : ": ", p);
    return error.what();
}

std::vector<std::string> backendNames() {
    std::vector<std::string> names;
    for (const Backend b : {Backend::Reference, Backend::Cpu, Backend::Cuda})
        names.push_back(backendName(b));
    return names;
}

CLI::Validator oneOf(std::vector<std::string> names) {
    const std::string list = fmt::format("{}", fmt::join(names, ", "));
    return CLI::Validator(
        [names, list](std::string& value) -> std::string {
            for (const std::string& n : names)
                if (n == value) return "";
            return fmt::format("'{}' is not one of {}{}", value, list, didYouMean(value, names));
        },
        "{" + list + "}");
}

CLI::Validator integerIn(long long lo, long long hi) {
    return CLI::Validator(
        [lo, hi](std::string& value) -> std::string {
            long long x = 0;
            size_t used = 0;
            try {
                x = std::stoll(value, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != value.size() || value.empty()) return "'" + value + "' is not an integer";
            if (x < lo || x > hi) return fmt::format("{} is outside [{}, {}]", value, lo, hi);
            return "";
        },
        fmt::format("[{}, {}]", lo, hi));
}

} // namespace bmfr::app
