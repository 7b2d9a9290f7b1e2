// Strict reading of JSON objects (scene descriptions, sequence.json): unknown keys are errors
// that suggest the nearest known key, and integers are integers in range.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bmfr {

/// Throws bmfr::Error naming `where` when `object` is not an object or has a key not in `known`
/// ("unknown key 'widht' in scene description (did you mean 'width'?)").
void requireKnownKeys(const nlohmann::json& object, const std::vector<std::string>& known,
                      const std::string& where);

/// object[key] as an integer in [lo, hi], or `fallback` when absent. A fraction, a string or a
/// value out of range is an error naming the key.
long long integerField(const nlohmann::json& object, const char* key, long long lo, long long hi,
                       long long fallback, const std::string& where);

/// `value` as a float: a finite number that a float holds (checked before the conversion);
/// anything else is an error naming `where`.
float floatValue(const nlohmann::json& value, const std::string& where);

/// object[key] as a finite number in [lo, hi], or `fallback` when absent.
double numberField(const nlohmann::json& object, const char* key, double lo, double hi,
                   double fallback, const std::string& where);

/// A JSON library error in a user's words, without the library's "[json.exception...]" tag:
/// `"view_projection" is missing`, `a value has the wrong type (...)`.
std::string jsonProblem(const nlohmann::json::exception& e);

} // namespace bmfr
