#include "io/json_fields.h"
#include "core/closest_name.h"
#include <algorithm>
#include <bmfr/error.h>
#include <cfloat>
#include <cmath>

namespace bmfr {

void requireKnownKeys(const nlohmann::json& object, const std::vector<std::string>& known,
                      const std::string& where) {
    if (!object.is_object()) throw Error(where + " must be a JSON object");
    for (auto it = object.begin(); it != object.end(); ++it) {
        if (std::find(known.begin(), known.end(), it.key()) != known.end()) continue;
        throw Error("unknown key '" + it.key() + "' in " + where + didYouMean(it.key(), known));
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

std::string jsonProblem(const nlohmann::json::exception& e) {
    std::string text = e.what();
    // nlohmann prefixes "[json.exception.out_of_range.403] ": the library's name, not the user's.
    if (text.rfind("[json.exception.", 0) == 0 && text.find("] ") != std::string::npos)
        text = text.substr(text.find("] ") + 2);
    const std::string missing = "key '";
    if (e.id == 403 && text.rfind(missing, 0) == 0) { // "key 'x' not found"
        const size_t end = text.find('\'', missing.size());
        std::string problem = "\"";
        problem.append(text, missing.size(), end - missing.size());
        return problem.append("\" is missing");
    }
    if (e.id >= 300 && e.id < 400) return "a value has the wrong type (" + text + ")";
    if (e.id >= 100 && e.id < 200) return "is not valid JSON (" + text + ")";
    return text;
}

} // namespace bmfr
