// A filter's settings as one table: key, command-line flag, unit, range and one-line help per
// setting, with the default taken from a default-constructed settings struct. Validation, the
// command line, `--help` and docs/settings.md's table are all made from it, so each range is
// written once.
#pragma once
#include <bmfr/error.h>
#include <bmfr/filter.h>
#include <cfloat>
#include <climits>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

namespace bmfr {

/// A numeric range; open ends are excluded. `integer` prints it without decimals.
struct SettingRange {
    double lo = 0, hi = 0;
    bool loOpen = false, hiOpen = false;
};

/// A setting stored as text with its own parser and printer (feature lists, enumerations).
template <class S> struct TextField {
    std::string (*get)(const S&);
    void (*set)(S&, const std::string&); ///< throws bmfr::Error with the reason
};

template <class S> struct Setting {
    const char* key;  ///< name in --set key=value, in the library and docs/settings.md
    const char* flag; ///< command-line flag without the dashes
    const char* unit; ///< "pixels", "scene units^2", "" for unitless
    SettingRange range;
    const char* help; ///< one line
    std::variant<float& (*)(S&), int& (*)(S&), uint32_t& (*)(S&), bool& (*)(S&), TextField<S>>
        field;
    /// Its value in the faithful preset (the paper's) where the default departs from it.
    const char* faithful = nullptr;
};

template <class S> using SettingsTable = std::vector<Setting<S>>;

/// Field accessors as plain function pointers: BMFR_FIELD(BmfrSettings, stages.taa).
#define BMFR_FIELD(S, member) (+[](S& s) -> decltype(auto) { return (s.member); })

namespace detail {
/// `text` as a number that the setting's type holds: in [lo, hi], and whole when `integer`.
double parseNumber(const std::string& key, const std::string& text, bool integer, double lo,
                   double hi);
bool parseBool(const std::string& key, const std::string& text);
std::string formatNumber(double v);
std::string formatRange(const SettingRange& r, bool integer);
void checkInRange(const char* filter, const char* key, double v, const SettingRange& r);
} // namespace detail

template <class S> bool isInteger(const Setting<S>& e) {
    return e.field.index() == 1 || e.field.index() == 2;
}
template <class S> bool isNumeric(const Setting<S>& e) {
    return e.field.index() <= 2;
}

/// The value of one setting as text.
template <class S> std::string formatSetting(const Setting<S>& e, const S& s) {
    S& m = const_cast<S&>(s); // the accessors take S&; nothing is written
    switch (e.field.index()) {
    case 0:
        return detail::formatNumber(std::get<0>(e.field)(m));
    case 1:
        return std::to_string(std::get<1>(e.field)(m));
    case 2:
        return std::to_string(std::get<2>(e.field)(m));
    case 3:
        return std::get<3>(e.field)(m) ? "true" : "false";
    default:
        return std::get<4>(e.field).get(s);
    }
}

/// Throws bmfr::Error when a numeric setting is outside its range.
template <class S> void checkSetting(const Setting<S>& e, const S& s, const char* filter) {
    S& m = const_cast<S&>(s);
    double v = 0;
    switch (e.field.index()) {
    case 0:
        v = std::get<0>(e.field)(m);
        break;
    case 1:
        v = std::get<1>(e.field)(m);
        break;
    case 2:
        v = std::get<2>(e.field)(m);
        break;
    default:
        return;
    }
    detail::checkInRange(filter, e.key, v, e.range);
}

/// Parses `text` into the setting (range-checked). Throws bmfr::Error naming the setting.
template <class S> void assignSetting(const Setting<S>& e, S& s, const std::string& text) {
    switch (e.field.index()) {
    case 0:
        std::get<0>(e.field)(s) = float(detail::parseNumber(e.key, text, false, -FLT_MAX, FLT_MAX));
        break;
    case 1:
        std::get<1>(e.field)(s) = int(detail::parseNumber(e.key, text, true, INT_MIN, INT_MAX));
        break;
    case 2:
        std::get<2>(e.field)(s) = uint32_t(detail::parseNumber(e.key, text, true, 0, UINT32_MAX));
        break;
    case 3:
        std::get<3>(e.field)(s) = detail::parseBool(e.key, text);
        return;
    default:
        try {
            std::get<4>(e.field).set(s, text);
        } catch (const Error& err) {
            throw SettingError(std::string("setting ") + e.key + ": " + err.what(), e.key, text,
                               err.what());
        }
        return;
    }
    checkSetting(e, s, "setting");
}

/// The entry whose key or flag is `name`, or null.
template <class S>
const Setting<S>* findSetting(const SettingsTable<S>& t, const std::string& name) {
    for (const Setting<S>& e : t)
        if (name == e.key || name == e.flag) return &e;
    return nullptr;
}

/// Applies key=value pairs in order. Throws bmfr::Error for a key the table lacks.
template <class S>
void applySettings(const SettingsTable<S>& t, S& s, const SettingValues& values,
                   const char* filter) {
    for (const auto& [key, value] : values) {
        const Setting<S>* e = findSetting(t, key);
        if (!e) throw Error("'" + key + "' is not a setting of the " + filter + " filter");
        assignSetting(*e, s, value);
    }
}

/// Range-checks every numeric entry.
template <class S> void checkSettings(const SettingsTable<S>& t, const S& s, const char* filter) {
    for (const Setting<S>& e : t) checkSetting(e, s, filter);
}

/// The table as documentation rows, defaults from S{}.
template <class S> std::vector<SettingDoc> documentSettings(const SettingsTable<S>& t, int shared) {
    const S defaults{};
    std::vector<SettingDoc> docs;
    for (size_t k = 0; k < t.size(); ++k) {
        const Setting<S>& e = t[k];
        SettingDoc d;
        d.key = e.key, d.flag = e.flag, d.unit = e.unit, d.help = e.help;
        d.range = isNumeric(e) ? detail::formatRange(e.range, isInteger(e))
                               : (e.field.index() == 3 ? "true, false" : "");
        d.defaultValue = formatSetting(e, defaults);
        d.faithful = e.faithful ? e.faithful : "";
        d.shared = int(k) < shared;
        docs.push_back(d);
    }
    return docs;
}

} // namespace bmfr
