#include "io/json_fields.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cfloat>
#include <cmath>

namespace bmfr {

namespace {

size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        size_t diagonal = row[0];
        row[0] = i;
        for (size_t j = 1; j <= b.size(); ++j) {
            const size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = up;
        }
    }
    return row[b.size()];
}

} // namespace

void requireKnownKeys(const nlohmann::json& object, const std::vector<std::string>& known,
                      const std::string& where) {
    if (!object.is_object()) throw Error(where + " must be a JSON object");
    for (auto it = object.begin(); it != object.end(); ++it) {
        if (std::find(known.begin(), known.end(), it.key()) != known.end()) continue;
        std::string best;
        size_t bestDistance = 3; // suggest only near misses
        for (const std::string& k : known)
            if (const size_t d = editDistance(it.key(), k); d < bestDistance) {
                best = k;
                bestDistance = d;
            }
        throw Error("unknown key '" + it.key() + "' in " + where +
                    (best.empty() ? "" : " (did you mean '" + best + "'?)"));
    }
}

long long integerField(const nlohmann::json& object, const char* key, long long lo, long long hi,
                       long long fallback, const std::string& where) {
    if (!object.contains(key)) return fallback;
    const nlohmann::json& v = object[key];
    long long x = 0;
    if (v.is_number_integer() && v.is_number_unsigned()) {
        const unsigned long long u = v.get<unsigned long long>();
        if (u > (unsigned long long)hi)
            throw Error(where + ": " + key + " = " + v.dump() + " is outside [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
        x = (long long)u;
    } else if (v.is_number_integer()) {
        x = v.get<long long>();
    } else if (v.is_number_float() && std::isfinite(v.get<double>()) &&
               v.get<double>() == std::floor(v.get<double>())) {
        // Range-checked as a double: converting one that a long long cannot hold is undefined.
        if (v.get<double>() < double(lo) || v.get<double>() > double(hi) ||
            std::fabs(v.get<double>()) >= 9.2e18)
            throw Error(where + ": " + key + " = " + v.dump() + " is outside [" +
                        std::to_string(lo) + ", " + std::to_string(hi) + "]");
        x = (long long)v.get<double>();
    } else {
        throw Error(where + ": " + key + " must be a whole number, got " + v.dump());
    }
    if (x < lo || x > hi)
        throw Error(where + ": " + key + " = " + std::to_string(x) + " is outside [" +
                    std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return x;
}

float floatValue(const nlohmann::json& value, const std::string& where) {
    if (!value.is_number() || !std::isfinite(value.get<double>()) ||
        std::fabs(value.get<double>()) > double(FLT_MAX))
        throw Error(where + " must be a finite number that a float holds, got " + value.dump());
    return float(value.get<double>());
}

double numberField(const nlohmann::json& object, const char* key, double lo, double hi,
                   double fallback, const std::string& where) {
    if (!object.contains(key)) return fallback;
    const nlohmann::json& v = object[key];
    if (!v.is_number() || !std::isfinite(v.get<double>()))
        throw Error(where + ": " + key + " must be a finite number, got " + v.dump());
    const double x = v.get<double>();
    if (x < lo || x > hi)
        throw Error(where + ": " + key + " = " + v.dump() + " is outside [" + std::to_string(lo) +
                    ", " + std::to_string(hi) + "]");
    return x;
}

} // namespace bmfr
