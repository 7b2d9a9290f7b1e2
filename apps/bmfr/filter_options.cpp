#include "filter_options.h"
#include "core/closest_name.h"
#include "usage.h"
#include <bmfr/error.h>
#include <cctype>
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

std::vector<std::string> keysOf(const std::vector<SettingDoc>& docs) {
    std::vector<std::string> keys;
    for (const SettingDoc& d : docs) keys.push_back(d.key);
    return keys;
}

std::vector<std::string> switchesOf(const std::vector<SettingDoc>& docs) {
    std::vector<std::string> flags;
    for (const SettingDoc& d : docs)
        if (d.range == "true, false") flags.push_back(d.flag);
    return flags;
}

/// " (it is a setting of walr)" for a flag another filter has, or "".
std::string ownerOf(const std::string& flag) {
    std::vector<std::string> owners;
    for (const std::string& f : filterNames())
        if (findDoc(filterSettings(f), flag)) owners.push_back(f);
    return owners.empty() ? std::string()
                          : fmt::format(" (it is a setting of {})", fmt::join(owners, ", "));
}

/// "BMFR", "SVGF", "WALR", "Mara 2017": the filter as its paper names it.
std::string filterTitle(const std::string& name) {
    return name == "mara2017" ? "Mara 2017" : upperCase(name);
}

std::string describe(const SettingDoc& d) {
    std::string s = d.help;
    if (!d.unit.empty()) s += "; " + d.unit;
    if (!d.range.empty() && d.range != "true, false") s += "; " + d.range;
    return s + "; default " + (d.defaultValue.empty() ? "none" : d.defaultValue);
}

} // namespace

void FilterOptions::addTo(CLI::App& cmd, const std::vector<std::string>& filters) {
    std::set<std::string> added;
    for (const std::string& f : filters)
        for (const SettingDoc& d : filterSettings(f)) {
            if (!added.insert(d.flag).second) continue;
            CLI::Option* o = cmd.add_option("--" + d.flag, flags[d.flag], describe(d));
            o->group(d.shared ? std::string("Settings of every filter")
                              : filterTitle(f) + " settings (--filter " + f + ")");
            if (d.range == "true, false") // a bare --flag means true
                o->expected(0, 1)->default_str("true")->type_name("[BOOL]");
            else
                o->type_name(d.range.empty() ? "TEXT" : "NUMBER");
        }
    cmd.add_option("--preset", preset,
                   "quality (the default: the papers' settings with the improvements beyond them) "
                   "or faithful (the papers' settings alone, the reproduction; `bmfr settings "
                   "FILTER --preset faithful` lists what it sets back); flags and --set override "
                   "it")
        ->check(oneOf(presetNames()))
        ->default_val("quality")
        ->group("Options");
    cmd.add_option("--set", sets,
                   "any setting as key=value (keys: `bmfr settings FILTER`); repeatable")
        ->group("Options");
    cmd.add_option("--disable", disabled,
                   "switches to turn off, comma-separated: demodulate, accumulation, fitting, "
                   "second-accumulation, taa")
        ->delimiter(',')
        ->group("Options");
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
        if (!d)
            throw UsageError("--" + flag + " is not a setting of the " + name + " filter" +
                             ownerOf(flag));
        v.push_back({d->key, text});
    }
    for (const std::string& s : sets) v.push_back(parseSetting(name, s, "--set"));
    for (const std::string& s : disabled) {
        const SettingDoc* d = findDoc(docs, s);
        if (!d || d->range != "true, false")
            throw UsageError("--disable " + s + ": not a switch of the " + name + " filter" +
                             didYouMean(s, switchesOf(docs)));
        v.push_back({d->key, "false"});
    }
    return v;
}

std::pair<std::string, std::string> parseSetting(const std::string& filter, const std::string& text,
                                                 const std::string& flag) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos || eq == 0)
        throw UsageError(flag + " '" + text + "': expected KEY=VALUE (keys: bmfr settings " +
                         filter + ")");
    const std::string key = text.substr(0, eq);
    const std::vector<SettingDoc> docs = filterSettings(filter);
    const SettingDoc* d = findDoc(docs, key);
    if (!d) {
        const std::string hint = didYouMean(key, keysOf(docs));
        throw UsageError(flag + " " + text + ": '" + key + "' is not a setting of the " + filter +
                         " filter" +
                         (hint.empty() ? " (`bmfr settings " + filter + "` lists them)" : hint));
    }
    return {d->key, text.substr(eq + 1)};
}

SettingValues parseSharedSettings(const std::string& filter,
                                  const std::vector<std::string>& filters,
                                  const std::vector<std::string>& texts, const std::string& flag) {
    SettingValues v;
    if (filters.size() == 1) {
        for (const std::string& text : texts) v.push_back(parseSetting(filter, text, flag));
        return v;
    }
    for (const std::string& text : texts) {
        const size_t eq = text.find('=');
        if (eq == std::string::npos || eq == 0)
            throw UsageError(fmt::format("{} '{}': expected KEY=VALUE (keys: bmfr settings NAME, "
                                         "for {})",
                                         flag, text, fmt::join(filters, ", ")));
        const std::string key = text.substr(0, eq);
        bool anyHas = false, filterHas = false;
        std::vector<std::string> keys;
        for (const std::string& f : filters) {
            const std::vector<SettingDoc> docs = filterSettings(f);
            const bool has = findDoc(docs, key) != nullptr;
            anyHas = anyHas || has;
            filterHas = filterHas || (has && f == filter);
            for (const std::string& k : keysOf(docs)) keys.push_back(k);
        }
        if (!anyHas) {
            const std::string hint = didYouMean(key, keys);
            throw UsageError(fmt::format(
                "{} {}: '{}' is not a setting of {}{}", flag, text, key, fmt::join(filters, ", "),
                hint.empty() ? " (`bmfr settings NAME` lists them)" : hint));
        }
        if (filterHas) v.push_back(parseSetting(filter, text, flag));
    }
    return v;
}

std::unique_ptr<Filter> FilterOptions::makeFilter(const std::string& name,
                                                  const SettingValues& values,
                                                  const SequenceDefaults& sequence) const {
    try {
        return bmfr::makeFilter(name, values);
    } catch (const SettingError& e) {
        rethrow(name, e, sequence);
    }
}

void FilterOptions::rethrow(const std::string& name, const SettingError& e,
                            const SequenceDefaults& sequence) const {
    // The defaults and presets are valid, so a bad value was typed on this command line (a
    // usage error in the flag's words), unless it is one the sequence gave and the command
    // line did not replace: then it is the input's.
    const std::vector<SettingDoc> docs = filterSettings(name);
    bool typed = false;
    for (const auto& [flag, text] : flags)
        if (const SettingDoc* d = findDoc(docs, flag); d && !text.empty() && d->key == e.key())
            typed = true;
    for (const std::string& s : sets)
        if (const SettingDoc* d = findDoc(docs, s.substr(0, s.find('='))); d && d->key == e.key())
            typed = true;
    const bool fromSequence =
        (e.key() == "positionLimitSquared" && sequence.positionLimitSquared) ||
        (e.key() == "normalLimitSquared" && sequence.normalLimitSquared) ||
        (e.key() == "colorIsDemodulated" && sequence.colorIsDemodulated);
    if (typed || !fromSequence) throw UsageError(describeForCli(e, name));
    throw e;
}

std::string settingValue(const SettingValues& values, const std::string& key,
                         const std::string& fallback) {
    std::string r = fallback;
    for (const auto& [k, v] : values)
        if (k == key) r = v;
    return r;
}

} // namespace bmfr::app
