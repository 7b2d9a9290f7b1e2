#include "help_format.h"
#include "usage.h"
#include <map>
#include <sstream>

namespace bmfr::app {

namespace {

std::map<const CLI::App*, std::string>& intros() {
    static std::map<const CLI::App*, std::string> m;
    return m;
}

/// A switch that takes an optional true/false (`--taa`, `--taa false`).
bool isOptionalBool(const CLI::Option* opt) {
    return opt->get_type_name() == "[BOOL]";
}

/// A help line's width: descriptions wrap before it.
constexpr size_t kWidth = 100;

/// `text` wrapped at kWidth, the lines after the first indented by `indent`.
std::string wrapped(const std::string& text, size_t indent, size_t first) {
    std::string out, line;
    size_t used = first;
    std::istringstream words(text);
    for (std::string w; words >> w;) {
        if (!line.empty() && used + line.size() + 1 + w.size() > kWidth) {
            out += line + "\n" + std::string(indent, ' ');
            line.clear();
            used = indent;
        }
        line += (line.empty() ? "" : " ") + w;
    }
    return out + line;
}

} // namespace

HelpFormatter::HelpFormatter() {
    column_width(30);
}

std::string HelpFormatter::make_help(const CLI::App* app, std::string name,
                                     CLI::AppFormatMode mode) const {
    if (mode == CLI::AppFormatMode::Sub) return make_expanded(app);
    std::string s = make_description(app) + make_usage(app, name) + make_positionals(app) +
                    groups(app) + make_subcommands(app, mode) + "\n" + make_footer(app);
    for (size_t at; (at = s.find("\n\n\n")) != std::string::npos;) s.erase(at, 1);
    return s;
}

std::string HelpFormatter::groups(const CLI::App* app) const {
    // One filter's settings at a time: all four filters' would bury the command's own options.
    const CLI::Option* filter = nullptr;
    for (const CLI::Option* o : app->get_options())
        if (o->check_lname("filter")) filter = o;
    const std::string shown = !filter           ? ""
                              : filter->count() ? filter->results().front()
                                                : filter->get_default_str();
    std::string s, others;
    for (const std::string& group : app->get_groups()) {
        const size_t tag = group.find("(--filter ");
        if (filter && tag != std::string::npos && group.substr(tag) != "(--filter " + shown + ")") {
            others +=
                (others.empty() ? "" : ", ") + group.substr(tag + 10, group.size() - tag - 11);
            continue;
        }
        std::vector<const CLI::Option*> opts = app->get_options(
            [&](const CLI::Option* o) { return o->get_group() == group && o->nonpositional(); });
        if (!group.empty() && !opts.empty()) s += make_group(group, false, opts) + "\n";
    }
    if (!others.empty())
        s += wrapped("The other filters' settings (" + others + "): bmfr " + app->get_name() +
                         " --filter NAME --help; `bmfr settings` lists them all.",
                     0, 0) +
             "\n";
    return s;
}

std::string HelpFormatter::make_option(const CLI::Option* opt, bool positional) const {
    const std::string name = "  " + make_option_name(opt, positional) + make_option_opts(opt);
    const size_t column = get_column_width();
    std::string s = name;
    if (name.size() + 1 > column)
        s += "\n" + std::string(column, ' ');
    else
        s += std::string(column - name.size(), ' ');
    return s + wrapped(make_option_desc(opt), column, column) + "\n";
}

void setHelpIntro(const CLI::App* cmd, std::string text) {
    intros()[cmd] = std::move(text);
}

std::string HelpFormatter::make_description(const CLI::App*) const {
    return ""; // printed by make_usage, after the usage line
}

std::string HelpFormatter::make_usage(const CLI::App* app, std::string) const {
    const bool root = app->get_parent() == nullptr;
    std::string s = root ? "usage: bmfr COMMAND [options]" : usageLine(*app);
    s += "\n\n" + wrapped(app->get_description(), 0, 0) + "\n";
    if (const auto it = intros().find(app); it != intros().end()) s += "\n" + it->second + "\n";
    return s;
}

std::string HelpFormatter::make_option_name(const CLI::Option* opt, bool positional) const {
    if (positional) {
        return upperCase(opt->get_name(true, false));
    }
    std::string s;
    for (const std::string& n : opt->get_snames()) s += (s.empty() ? "-" : ", -") + n;
    for (const std::string& n : opt->get_lnames()) s += (s.empty() ? "--" : ", --") + n;
    return s;
}

std::string HelpFormatter::make_option_opts(const CLI::Option* opt) const {
    if (opt->get_type_size() == 0) return ""; // a plain flag
    if (isOptionalBool(opt)) return "[=true|false]";
    // A validator's choices in braces say more than the type: `{bmfr, svgf, walr, mara2017}`.
    const std::string type = opt->get_type_name();
    size_t choices = type.find(":{");
    if (choices == std::string::npos) choices = type.find(":[");
    std::string s = " " + (choices == std::string::npos ? type : type.substr(choices + 1));
    if (opt->get_expected_max() == CLI::detail::expected_max_vector_size) s += " ...";
    return s;
}

std::string HelpFormatter::make_option_desc(const CLI::Option* opt) const {
    std::string d = opt->get_description();
    const std::string def = opt->get_default_str();
    if (opt->get_required()) return d + " (required)";
    if (!def.empty() && d.find("default") == std::string::npos) d += "; default " + def;
    return d;
}

} // namespace bmfr::app
