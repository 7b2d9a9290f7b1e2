#include "core/settings_table.h"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace bmfr::detail {

namespace {

[[noreturn]] void badText(const std::string& key, const std::string& text, const char* problem) {
    throw SettingError("setting " + key + ": '" + text + "' " + problem, key, text, problem);
}

} // namespace

double parseNumber(const std::string& key, const std::string& text, bool integer, double lo,
                   double hi) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(v)) badText(key, text, "is not a number");
    if (integer && v != std::floor(v)) badText(key, text, "is not a whole number");
    // Checked before the conversion: a value the type cannot hold is undefined behaviour.
    if (v < lo || v > hi) {
        char range[96];
        if (integer)
            std::snprintf(range, sizeof range, "is outside [%lld, %lld]", (long long)lo,
                          (long long)hi);
        else
            std::snprintf(range, sizeof range, "is outside the range of a float");
        badText(key, text, range);
    }
    return v;
}

bool parseBool(const std::string& key, const std::string& text) {
    if (text == "true" || text == "1" || text == "on" || text == "yes") return true;
    if (text == "false" || text == "0" || text == "off" || text == "no") return false;
    badText(key, text, "is not true or false");
}

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string formatRange(const SettingRange& r, bool integer) {
    auto num = [&](double v) {
        if (v >= 1e29) return std::string("inf");
        return integer ? std::to_string(long(v)) : formatNumber(v);
    };
    return std::string(r.loOpen ? "(" : "[") + num(r.lo) + ", " + num(r.hi) +
           (r.hiOpen || r.hi >= 1e29 ? ")" : "]");
}

void checkInRange(const char* filter, const char* key, double v, const SettingRange& r) {
    const bool ok =
        std::isfinite(v) && (r.loOpen ? v > r.lo : v >= r.lo) && (r.hiOpen ? v < r.hi : v <= r.hi);
    if (!ok) {
        const std::string problem = "is outside " + formatRange(r, false);
        throw SettingError(std::string(filter) + " " + key + " = " + formatNumber(v) + " " +
                               problem,
                           key, formatNumber(v), problem);
    }
}

} // namespace bmfr::detail
