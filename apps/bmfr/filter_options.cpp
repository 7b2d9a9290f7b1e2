#include "filter_options.h"
#include <bmfr/error.h>
#include <fmt/format.h>
#include <set>

namespace bmfr::app {

namespace {

/// The table row of `name` (key or flag) in `docs`, or null.
const SettingDoc* findDoc(const std::vector<SettingDoc>& docs, const std::string& name) {
    for (const SettingDoc& d : docs)
        if (d.key == name || d.flag == name) return &d;
    return nullptr;
}

std::string describe(const SettingDoc& d) {
    std::string s = d.help;
    if (!d.unit.empty()) s += "; " + d.unit;
    if (!d.range.empty()) s += "; " + d.range;
    return s + "; default " + (d.defaultValue.empty() ? "none" : d.defaultValue);
}

} // namespace

void FilterOptions::addTo(CLI::App& cmd, const std::vector<std::string>& filters) {
    std::set<std::string> added;
    for (const std::string& f : filters)
        for (const SettingDoc& d : filterSettings(f)) {
            if (!added.insert(d.flag).second) continue;
            const std::string help = (d.shared ? std::string() : "[" + f + "] ") + describe(d);
            CLI::Option* o = cmd.add_option("--" + d.flag, flags[d.flag], help);
            if (d.range == "true, false") // a bare --flag means true
                o->expected(0, 1)->default_str("true")->type_name("[BOOL]");
            else
                o->type_name(d.range.empty() ? "TEXT" : "NUMBER");
        }
    cmd.add_option("--preset", preset,
                   "faithful (the papers' settings) or quality (with the improvements beyond "
                   "them; `bmfr settings FILTER --preset quality` lists them); flags and --set "
                   "override it")
        ->check(CLI::IsMember(presetNames()))
        ->default_val("faithful");
    cmd.add_option("--set", sets,
                   "any setting as key=value (keys: `bmfr settings FILTER`); repeatable");
    cmd.add_option("--disable", disabled,
                   "switches to turn off, comma-separated: demodulate, accumulation, fitting, "
                   "second-accumulation, taa")
        ->delimiter(',');
}

SettingValues FilterOptions::resolve(const std::string& name, const SequenceDefaults& seq) const {
    const std::vector<SettingDoc> docs = filterSettings(name);
    SettingValues v;
    auto number = [](float x) { return fmt::format("{}", x); }; // shortest exact form
    if (seq.positionLimitSquared)
        v.push_back({"positionLimitSquared", number(*seq.positionLimitSquared)});
    if (seq.normalLimitSquared)
        v.push_back({"normalLimitSquared", number(*seq.normalLimitSquared)});
    if (seq.colorIsDemodulated) v.push_back({"colorIsDemodulated", "true"});
    for (const auto& kv : presetSettings(name, preset)) v.push_back(kv);
    for (const auto& [flag, text] : flags) {
        if (text.empty()) continue; // not given
        const SettingDoc* d = findDoc(docs, flag);
        if (!d) throw Error("--" + flag + " is not a setting of the " + name + " filter");
        v.push_back({d->key, text});
    }
    for (const std::string& s : sets) {
        const size_t eq = s.find('=');
        if (eq == std::string::npos || eq == 0)
            throw Error("--set '" + s + "': expected key=value");
        const SettingDoc* d = findDoc(docs, s.substr(0, eq));
        if (!d)
            throw Error("--set: '" + s.substr(0, eq) + "' is not a setting of the " + name +
                        " filter");
        v.push_back({d->key, s.substr(eq + 1)});
    }
    for (const std::string& s : disabled) {
        const SettingDoc* d = findDoc(docs, s);
        if (!d || d->range != "true, false")
            throw Error("--disable: unknown stage '" + s + "' for the " + name + " filter");
        v.push_back({d->key, "false"});
    }
    return v;
}

std::string settingValue(const SettingValues& values, const std::string& key,
                         const std::string& fallback) {
    std::string r = fallback;
    for (const auto& [k, v] : values)
        if (k == key) r = v;
    return r;
}

} // namespace bmfr::app
